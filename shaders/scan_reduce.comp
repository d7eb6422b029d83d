#version 460
#extension GL_GOOGLE_include_directive : require
// PrefixScan step 1: the sum of each block of input, written to the scratch's block sums.
// Workgroups walk the blocks in a grid-stride loop (there may be more than 65535 blocks).
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "buffers.glsl"

layout(local_size_x_id = 0) in;
layout(constant_id = 1) const uint ITEMS = 16;          // elements per invocation and block
layout(constant_id = 2) const uint MAX_SUBGROUPS = 32;  // workgroup size / smallest subgroup size
#define WGS_MAX_SUBGROUPS MAX_SUBGROUPS
#include "workgroup_scan.glsl"

const uint SUMS = 16;  // first block sum in the control words

layout(push_constant) uniform Push {
    Uints input_values;
    Uints control;
} pc;

void main() {
    const uint count = pc.control.v[3];
    const uint blocks = pc.control.v[4];
    const uint block_size = gl_WorkGroupSize.x * ITEMS;
    for (uint block = gl_WorkGroupID.x; block < blocks; block += gl_NumWorkGroups.x) {
        const uint start = block * block_size;
        uint sum = 0;
        for (uint i = 0; i < ITEMS; ++i) {
            const uint index = start + i * gl_WorkGroupSize.x + gl_LocalInvocationIndex;
            if (index < count) sum += pc.input_values.v[index];
        }
        const uint total = workgroup_add(sum);
        if (gl_LocalInvocationIndex == 0) pc.control.v[SUMS + block] = total;
    }
}
