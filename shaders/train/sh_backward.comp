#version 460
// SH backward: the gradients of every Gaussian's SH coefficients, from what
// preprocess_backward.comp left per Gaussian in pc.sh_steps: d L / d coefficient k = basis_k(view
// direction) x d L / d colour. In a training step (pc.adam set) each goes straight into Adam
// (adam.glsl) with the DC coefficient's rate or the rest's; otherwise it is written to pc.grads.
// Bands above the frame's degree get zero gradients (their moments decay, as torch's dense Adam
// does); a Gaussian whose gradient was not finite does not step.
// A thread takes four consecutive floats ([Gaussian][coefficient][rgb]) as one 16-byte load of
// each array where they lie in one aligned vec4 (every gpu::Buffer is an allocation of its own,
// so its start is aligned; all but the block's two ends, since the block starts at 11 N floats),
// so the parameters and moments move in whole cache lines with a quarter of the memory
// instructions (bonsai at 400,000 Gaussians on an H200: 0.155 ms a step, 0.183 with a 4-byte
// load per float); it loads all of their states before it stores any (adam.glsl says why). A
// thread per coefficient, three floats apart, was slower still (0.278 ms).
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
    // The block's floats are [first, end) of the array; chunk c is its floats [4c, 4c + 4).
    const uint first = sh_offset(n), end = first + n * sh_floats;
    if (first == end) return;
    const uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    for (uint c = first / 4u + gl_GlobalInvocationID.x; 4u * c < end; c += stride) {
        float grad[4];
        bool steps[4];
        [[unroll]] for (uint u = 0u; u < 4u; ++u) {
            const uint at = 4u * c + u;
            const uint j = min(max(at, first), end - 1u) - first;  // clamped: lanes outside the block
            const uint g = j / sh_floats, within = j - g * sh_floats, k = within / 3u;
            const vec4 dir = pc.sh_steps.v[2u * g];
            steps[u] = at >= first && at < end && dir.w != 0.0;
            grad[u] = k < used ? sh_basis_function(k, dir.xyz) * pc.sh_steps.v[2u * g + 1u][within - 3u * k] : 0.0;
        }
        if (!fused) {
            [[unroll]] for (uint u = 0u; u < 4u; ++u)
                if (steps[u]) pc.grads.v[4u * c + u] = grad[u];
            continue;
        }
        const bool whole = 4u * c >= first && 4u * c + 4u <= end;
        if (!whole) {  // the block's first or last chunk, float by float
            [[unroll]] for (uint u = 0u; u < 4u; ++u) {
                const uint at = 4u * c + u;
                if (!steps[u]) continue;
                const float rate = (at - first) % sh_floats < 3u ? adam.lr_sh_dc : adam.lr_sh_rest;
                adam_store(adam, pc.raw, at, adam_load(adam, pc.raw, at), grad[u], rate);
            }
            continue;
        }
        if (!(steps[0] || steps[1] || steps[2] || steps[3])) continue;
        const vec4 param = Vec4s(pc.raw).v[c], m = Vec4s(adam.first_moment).v[c], v = Vec4s(adam.second_moment).v[c];
        vec4 next_param = param, next_m = m, next_v = v;
        [[unroll]] for (uint u = 0u; u < 4u; ++u) {
            if (!steps[u]) continue;  // written back unchanged
            const float rate = (4u * c + u - first) % sh_floats < 3u ? adam.lr_sh_dc : adam.lr_sh_rest;
            const AdamState next = adam_step(adam, AdamState(param[u], m[u], v[u]), grad[u], rate);
            next_param[u] = next.param;
            next_m[u] = next.m;
            next_v[u] = next.v;
        }
        Vec4s(pc.raw).v[c] = next_param;
        Vec4s(adam.first_moment).v[c] = next_m;
        Vec4s(adam.second_moment).v[c] = next_v;
    }
}
