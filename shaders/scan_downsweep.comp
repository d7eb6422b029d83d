#version 460
#extension GL_GOOGLE_include_directive : require
// PrefixScan step 3: each block is loaded into shared memory, scanned there (ITEMS consecutive
// elements per invocation + a workgroup scan of their sums), offset by the block's scanned sum
// and written out. Reads all of a block before writing any of it, so input may equal output.
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "buffers.glsl"

layout(local_size_x_id = 0) in;
layout(constant_id = 1) const uint ITEMS = 16;
layout(constant_id = 2) const uint MAX_SUBGROUPS = 32;
#define WGS_MAX_SUBGROUPS MAX_SUBGROUPS
#include "workgroup_scan.glsl"

const uint SUMS = 16;

layout(push_constant) uniform Push {
    Uints input_values;
    Uints output_values;
    Uints control;
} pc;

shared uint tile[gl_WorkGroupSize.x * ITEMS];

void main() {
    const uint count = pc.control.v[3];
    const uint blocks = pc.control.v[4];
    const uint size = gl_WorkGroupSize.x;
    const uint block_size = size * ITEMS;
    // Position of this invocation in the workgroup scan's order.
    const uint local = gl_SubgroupID * gl_SubgroupSize + gl_SubgroupInvocationID;
    for (uint block = gl_WorkGroupID.x; block < blocks; block += gl_NumWorkGroups.x) {
        const uint start = block * block_size;
        for (uint i = 0; i < ITEMS; ++i) {
            const uint j = i * size + gl_LocalInvocationIndex;
            tile[j] = start + j < count ? pc.input_values.v[start + j] : 0u;
        }
        barrier();
        uint sum = 0;
        for (uint i = 0; i < ITEMS; ++i) sum += tile[local * ITEMS + i];
        uint block_total;
        uint running = pc.control.v[SUMS + block] + workgroup_exclusive_add(sum, block_total);
        for (uint i = 0; i < ITEMS; ++i) {
            const uint v = tile[local * ITEMS + i];
            tile[local * ITEMS + i] = running;
            running += v;
        }
        barrier();
        for (uint i = 0; i < ITEMS; ++i) {
            const uint j = i * size + gl_LocalInvocationIndex;
            if (start + j < count) pc.output_values.v[start + j] = tile[j];
        }
        barrier();
    }
}
