#version 460
// The per-splat gradient totals blend_backward_fixed.comp summed as 64-bit integers, as the floats
// preprocess_backward.comp reads (shaders/train/differentiable_renderer.h).
#extension GL_GOOGLE_include_directive : require
#define FIXED_POINT_SUMS 1
#include "shaders/common/buffers.h"
#include "shaders/train/differentiable_renderer.h"

layout(local_size_x = 256) in;

layout(push_constant) uniform Push { SplatGradsFromFixedPush pc; };

void main() {
    for (uint i = gl_GlobalInvocationID.x; i < pc.count; i += gl_NumWorkGroups.x * gl_WorkGroupSize.x)
        pc.splat_grads.v[i] = float(pc.totals.v[i]) * (1.0 / SPLAT_GRAD_FIXED_SCALE);  // a power of 2: exact
}
