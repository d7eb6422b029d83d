#version 460
// SH backward: the gradients of every Gaussian's SH coefficients, one thread per float, from what
// preprocess_backward.comp left per Gaussian in pc.sh_steps: d L / d coefficient k = basis_k(view
// direction) x d L / d colour. In a training step (pc.adam set) each goes straight into Adam
// (adam.glsl) with the DC coefficient's rate or the rest's; otherwise it is written to pc.grads.
// Bands above the frame's degree get zero gradients (their moments decay, as torch's dense Adam
// does); a Gaussian whose gradient was not finite does not step.
// Consecutive threads take consecutive floats ([Gaussian][coefficient][rgb]), so the parameters
// and moments move in whole cache lines, and each thread loads the states of four floats before
// it stores any (adam.glsl says why).
#extension GL_GOOGLE_include_directive : require
#include "shaders/train/differentiable_renderer.h"
layout(push_constant) uniform Push { ShBackwardPush pc; };
#include "shaders/common/buffers.h"
#include "shaders/render/frame.h"
#include "shaders/render/sh.glsl"
#include "shaders/train/adam.glsl"

layout(local_size_x = 256) in;

void main() {
    const CameraParams cam = pc.camera.c;
    // preprocess_backward.comp stepped nothing in a frame that overflowed, nor behind one, nor
    // where the fixed-point sums lost a gradient, and left no directions.
    if (pc.counters.v[COUNTER_ENTRIES_NEEDED] > cam.entry_capacity || pc.status.v[STATUS_OVERFLOW_MARK] != 0u)
        return;
    const bool fused = (pc.adam.x | pc.adam.y) != 0u;
    if (fused && (pc.status.v[0] & STEP_NONFINITE_SUMS) != 0u) return;  // as preprocess_backward.comp
    AdamSettings adam;
    if (fused) adam = AdamSettingsBuffer(pc.adam).s;
    const uint n = cam.gaussian_count;
    const uint sh_floats = 3u * cam.sh_stride;
    const uint used = (cam.sh_degree + 1u) * (cam.sh_degree + 1u);  // coefficients the frame used
    const uint floats = n * sh_floats, base = sh_offset(n);
    const uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    for (uint j0 = gl_GlobalInvocationID.x; j0 < floats; j0 += 4u * stride) {
        float grad[4];
        bool steps[4];
        AdamState state[4];
        [[unroll]] for (uint u = 0u; u < 4u; ++u) {
            const uint j = j0 + u * stride;
            const uint g = min(j, floats - 1u) / sh_floats, within = j - g * sh_floats, k = within / 3u;
            const vec4 dir = pc.sh_steps.v[2u * g];
            steps[u] = j < floats && dir.w != 0.0;
            grad[u] = k < used ? sh_basis_function(k, dir.xyz) * pc.sh_steps.v[2u * g + 1u][within - 3u * k] : 0.0;
            if (steps[u] && fused) state[u] = adam_load(adam, pc.raw, base + j);
        }
        [[unroll]] for (uint u = 0u; u < 4u; ++u) {
            const uint j = j0 + u * stride;
            if (!steps[u]) continue;
            if (!fused) {
                pc.grads.v[base + j] = grad[u];
                continue;
            }
            const float rate = j % sh_floats < 3u ? adam.lr_sh_dc : adam.lr_sh_rest;
            adam_store(adam, pc.raw, base + j, state[u], grad[u], rate);
        }
    }
}
