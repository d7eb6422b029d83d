#version 460
// A Rademacher probe: each channel of each pixel gets dL/d rgb = +1 or -1, independently. With
// these as the upstream gradient the backward pass returns G = sum over pixels p and channels c of
// eps_pc g_pc, and E[G G^T] = sum of g_pc g_pc^T (the cross terms have mean 0): the Fisher
// information, one rank-one term per probe.
#extension GL_GOOGLE_include_directive : require

#include "shaders/common/buffers.h"
#include "shaders/common/hash.glsl"
#include "shaders/train/fisher_probes.h"

layout(local_size_x = 256) in;

layout(push_constant) uniform Push { FisherProbeSignsPush pc; };

float sign_bit(uint bits, uint k) { return ((bits >> k) & 1u) != 0u ? 1.0 : -1.0; }

void main() {
    for (uint p = gl_GlobalInvocationID.x; p < pc.pixels; p += gl_NumWorkGroups.x * gl_WorkGroupSize.x) {
        // The hash's high bits are its best mixed.
        const uint bits = pcg_hash(pc.seed ^ pcg_hash(p)) >> 29u;
        pc.pixel_grad.v[p] = vec4(sign_bit(bits, 0u), sign_bit(bits, 1u), sign_bit(bits, 2u), 0.0);
    }
}
