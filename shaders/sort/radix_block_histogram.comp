#version 460
#extension GL_GOOGLE_include_directive : require
// RadixSort, a pass of a large sort, step 1: each workgroup counts the digits of its blocks of
// keys, writes hist[digit * blocks + block] and adds them to the pass's per-digit totals (cleared
// by radix_setup), from which radix_scan_histogram gives every (digit, block) its first output
// position for radix_scatter. Workgroups walk the blocks in a grid-stride loop.
#include "shaders/sort/radix_sort.h"

layout(local_size_x_id = 0) in;
layout(constant_id = 1) const uint ITEMS = 16;  // keys per invocation and block

layout(push_constant) uniform Push { RadixBlockHistogramPush pc; };

shared uint counts[RADIX_MAX];

void main() {
    const uint count = pc.control.v[3];
    const uint blocks = pc.control.v[4];
    const uint size = gl_WorkGroupSize.x;
    const uint radix = 1u << pc.bits;
    const uint mask = radix - 1u;
    for (uint block = gl_WorkGroupID.x; block < blocks; block += gl_NumWorkGroups.x) {
        for (uint d = gl_LocalInvocationIndex; d < radix; d += size) counts[d] = 0;
        barrier();
        const uint start = block * size * ITEMS;
        // All loads first, so that they overlap (see radix_rank_block).
        uint keys[ITEMS];
        for (uint i = 0; i < ITEMS; ++i) {
            const uint index = start + i * size + gl_LocalInvocationIndex;
            keys[i] = index < count ? pc.keys.v[index] : 0u;
        }
        for (uint i = 0; i < ITEMS; ++i)
            if (start + i * size + gl_LocalInvocationIndex < count) atomicAdd(counts[(keys[i] >> pc.shift) & mask], 1u);
        barrier();
        for (uint d = gl_LocalInvocationIndex; d < radix; d += size) {
            pc.hist.v[d * blocks + block] = counts[d];
            if (counts[d] != 0u) atomicAdd(pc.totals.v[d], counts[d]);
        }
        barrier();
    }
}
