#version 460
#extension GL_GOOGLE_include_directive : require
// PrefixScan step 2 (one workgroup): exclusive scan of the block sums in place, looping over any
// number of them; writes the grand total to `total` when that address is not null.
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include "buffers.glsl"

layout(local_size_x_id = 0) in;
layout(constant_id = 1) const uint ITEMS = 16;
layout(constant_id = 2) const uint MAX_SUBGROUPS = 32;
#define WGS_MAX_SUBGROUPS MAX_SUBGROUPS
#include "workgroup_scan.glsl"

const uint SUMS = 16;

layout(push_constant) uniform Push {
    Uints control;
    uvec2 total;  // device address of one uint, or 0
} pc;

void main() {
    const uint blocks = pc.control.v[4];
    uint carry = 0;
    // Each invocation takes ITEMS consecutive sums per round, so a round covers a whole tile.
    const uint tile = gl_WorkGroupSize.x * ITEMS;
    const uint local = gl_SubgroupID * gl_SubgroupSize + gl_SubgroupInvocationID;
    for (uint base = 0; base < blocks; base += tile) {
        const uint first = base + local * ITEMS;
        uint sum = 0;
        for (uint i = 0; i < ITEMS; ++i)
            if (first + i < blocks) sum += pc.control.v[SUMS + first + i];
        uint round_total;
        uint running = carry + workgroup_exclusive_add(sum, round_total);
        for (uint i = 0; i < ITEMS; ++i) {
            if (first + i < blocks) {
                const uint v = pc.control.v[SUMS + first + i];
                pc.control.v[SUMS + first + i] = running;
                running += v;
            }
        }
        carry += round_total;
    }
    if (gl_LocalInvocationIndex == 0 && (pc.total.x | pc.total.y) != 0) Uints(pc.total).v[0] = carry;
}
