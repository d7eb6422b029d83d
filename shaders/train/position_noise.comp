#version 460
// 3DGS-MCMC's exploration noise (Kheradmand et al. 2024, "3D Gaussian Splatting as Markov Chain
// Monte Carlo", eq. 10): after each step every position moves by
//   scale * gate(1 - opacity) * Sigma * eps,   eps ~ N(0, I),
//   gate(x) = 1 / (1 + exp(-100 (x - 0.995))),
// so a Gaussian that is nearly transparent (opacity below ~0.005) wanders along its own shape and
// can be found useful elsewhere, while the ones that make the picture stay put (gate ~ 0). The
// noise comes from a hash of (seed, Gaussian, axis): a run repeats exactly, on any device.
#extension GL_GOOGLE_include_directive : require

#include "shaders/common/buffers.h"
#include "shaders/common/gaussian_shape.glsl"
#include "shaders/common/hash.glsl"
#include "shaders/train/position_noise.h"

layout(local_size_x = 256) in;

layout(push_constant) uniform Push { PositionNoisePush pc; };

// A uniform number in (0, 1]: never 0, whose log Box-Muller takes.
float uniform01(uint v) { return (float(pcg_hash(v) >> 8u) + 1.0) / 16777216.0; }

// Three standard normal numbers for Gaussian i (Box-Muller on hashed uniforms).
vec3 normal3(uint i) {
    const uint base = pcg_hash(pc.seed ^ pcg_hash(i));
    vec3 result;
    for (uint k = 0u; k < 3u; ++k) {
        const float radius = sqrt(-2.0 * log(uniform01(base + 2u * k)));
        result[k] = radius * cos(6.28318530718 * uniform01(base + 2u * k + 1u));
    }
    return result;
}

void main() {
    if (pc.status.v[0] != 0u) return;
    const uint n = pc.count;
    for (uint i = gl_GlobalInvocationID.x; i < n; i += gl_NumWorkGroups.x * gl_WorkGroupSize.x) {
        const float opacity = sigmoid(pc.params.v[opacities_offset(n) + i]);
        const float gate = sigmoid(100.0 * ((1.0 - opacity) - 0.995));
        if (gate * pc.scale == 0.0) continue;
        const uint s = log_scales_offset(n) + 3u * i, r = rotations_offset(n) + 4u * i;
        const vec3 scale = exp(vec3(pc.params.v[s], pc.params.v[s + 1u], pc.params.v[s + 2u]));
        const vec4 q = vec4(pc.params.v[r], pc.params.v[r + 1u], pc.params.v[r + 2u], pc.params.v[r + 3u]);
        const float length_q = length(q);
        if (!(length_q > 0.0)) continue;  // sanitised away at upload; a degenerate step skips it
        const vec3 step = pc.scale * gate * (covariance_3d(scale, q / length_q) * normal3(i));
        // A non-finite step would poison the position for good: such a Gaussian stays where it is.
        if (any(isnan(step)) || any(isinf(step))) continue;
        const uint p = positions_offset(n) + 3u * i;
        for (uint k = 0u; k < 3u; ++k) pc.params.v[p + k] += step[k];
    }
}
