#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_vote : require
// RadixSort, a one-sweep sort, step 1 (once, not per pass): counts the digits of every pass over all keys.
// A key's digit in a later pass does not depend on the order earlier passes leave, so one read of
// the keys gives every pass's per-digit totals, from which each pass's scatter takes the first
// output position of each digit. It also clears its blocks' look-back words for every pass (the
// scatter reads them after the barrier that follows), so they need no clear of their own.
// Workgroups walk the blocks in a grid-stride loop.
#include "shaders/sort/radix_sort.h"

layout(local_size_x_id = 0) in;
layout(constant_id = 1) const uint ITEMS = 16;  // keys per invocation and block
#include "shaders/sort/radix_digit_counts.glsl"

layout(push_constant) uniform Push { RadixHistogramPush pc; };

void main() {
    const uint count = pc.control.v[3];
    const uint blocks = pc.control.v[4];
    const uint size = gl_WorkGroupSize.x;
    const uint local = gl_LocalInvocationIndex;
    radix_clear_digit_counts();
    barrier();
    for (uint block = gl_WorkGroupID.x; block < blocks; block += gl_NumWorkGroups.x) {
        for (uint i = local; i < pc.passes * RADIX_MAX; i += size)
            pc.lookback.v[lookback_index(block, 0, 0) + i] = LOOKBACK_EMPTY;
        const uint start = block * size * ITEMS;
        // All loads first, so that they overlap (see radix_rank_block).
        uint keys[ITEMS];
        for (uint i = 0; i < ITEMS; ++i) {
            const uint index = start + i * size + local;
            keys[i] = index < count ? pc.keys.v[index] : 0u;
        }
        for (uint i = 0; i < ITEMS; ++i) {
            if (start + i * size + local >= count) break;
            radix_count_digits(keys[i], pc.digits, pc.passes);
        }
    }
    radix_add_digit_counts(pc.totals, pc.passes);
}
