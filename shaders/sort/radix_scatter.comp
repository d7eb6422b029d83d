#version 460
#extension GL_GOOGLE_include_directive : require
// RadixSort, a pass of a large sort, step 3: each workgroup re-reads its blocks and moves every
// (key, value) to its stable position (ranking and writing: radix_block.glsl; the one-sweep kernel
// takes the first term below from totals and look-back instead). Output position of a key =
//   scanned hist[digit * blocks + block]   (keys of smaller digits, and of its digit in earlier blocks)
// + its rank among the block's keys of its digit (earlier subgroups' parts, then earlier rows
//   and lanes of its own part).
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "shaders/sort/radix_sort.h"

layout(local_size_x_id = 0) in;
layout(constant_id = 1) const uint ITEMS = 16;          // rows per subgroup = keys per invocation
layout(constant_id = 2) const uint MAX_SUBGROUPS = 16;  // workgroup size / smallest subgroup size
#define WGS_MAX_SUBGROUPS MAX_SUBGROUPS
#include "shaders/common/workgroup_scan.glsl"

const uint DIGITS_PER_INVOCATION = (RADIX_MAX + gl_WorkGroupSize.x - 1) / gl_WorkGroupSize.x;

layout(push_constant) uniform Push { RadixScatterPush pc; };

#include "shaders/sort/radix_block.glsl"

void main() {
    const uint count = pc.control.v[3];
    const uint blocks = pc.control.v[4];
    const uint mask = (1u << pc.bits) - 1u;
    const uint digit0 = (gl_SubgroupID * gl_SubgroupSize + gl_SubgroupInvocationID) * DIGITS_PER_INVOCATION;

    for (uint block = gl_WorkGroupID.x; block < blocks; block += gl_NumWorkGroups.x) {
        uint keys[ITEMS], values[ITEMS], ranks[ITEMS];
        radix_rank_block(block, count, mask, keys, values, ranks);

        // Block-local positions: each invocation takes DIGITS_PER_INVOCATION consecutive digits,
        // scans them over the subgroups, and a workgroup scan (in the order below) orders the digits.
        uint digit_count[DIGITS_PER_INVOCATION];
        uint my_keys = 0;
        for (uint i = 0; i < DIGITS_PER_INVOCATION; ++i) {
            digit_count[i] = digit0 + i < RADIX_MAX ? radix_scan_digit(digit0 + i) : 0u;
            my_keys += digit_count[i];
        }
        uint block_keys;
        uint local_start = workgroup_exclusive_add(my_keys, block_keys);
        for (uint i = 0; i < DIGITS_PER_INVOCATION; ++i) {
            const uint d = digit0 + i;
            if (d < RADIX_MAX) {
                radix_offset_digit(d, local_start);
                if (digit_count[i] != 0) displacement[d] = pc.hist.v[d * blocks + block] - local_start;
            }
            local_start += digit_count[i];
        }
        radix_write_block(block_keys, mask, keys, values, ranks);
    }
}
