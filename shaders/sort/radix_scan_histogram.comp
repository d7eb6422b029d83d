#version 460
#extension GL_GOOGLE_include_directive : require
// RadixSort, a pass of a large sort, step 2: turns the per-block digit counts into output positions in one
// dispatch (a general prefix scan would take four, each behind a barrier, and at a few
// microseconds apiece those dominated sorts of a few hundred thousand keys). Workgroup d owns
// digit d: its first position is the number of keys with a smaller digit (the histogram kernel
// summed every digit's total), and its blocks' positions follow by a scan along hist[d][block].
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "shaders/sort/radix_sort.h"

layout(local_size_x_id = 0) in;
layout(constant_id = 1) const uint ITEMS = 16;
layout(constant_id = 2) const uint MAX_SUBGROUPS = 32;
#define WGS_MAX_SUBGROUPS MAX_SUBGROUPS
#include "shaders/common/workgroup_scan.glsl"

layout(push_constant) uniform Push { RadixScanHistogramPush pc; };

void main() {
    const uint digit = gl_WorkGroupID.x;
    if (digit >= (1u << pc.bits)) return;  // uniform: the whole workgroup leaves
    const uint blocks = pc.control.v[4];
    const uint local = gl_SubgroupID * gl_SubgroupSize + gl_SubgroupInvocationID;

    uint smaller = 0;
    for (uint d = local; d < digit; d += gl_WorkGroupSize.x) smaller += pc.totals.v[d];
    uint carry = workgroup_add(smaller);

    // Each invocation takes ITEMS consecutive blocks per round.
    const uint round_size = gl_WorkGroupSize.x * ITEMS;
    const uint row = digit * blocks;
    for (uint base = 0; base < blocks; base += round_size) {
        const uint first = base + local * ITEMS;
        uint sum = 0;
        for (uint i = 0; i < ITEMS; ++i)
            if (first + i < blocks) sum += pc.hist.v[row + first + i];
        uint round_total;
        uint running = carry + workgroup_exclusive_add(sum, round_total);
        for (uint i = 0; i < ITEMS; ++i) {
            if (first + i < blocks) {
                const uint v = pc.hist.v[row + first + i];
                pc.hist.v[row + first + i] = running;
                running += v;
            }
        }
        carry += round_total;
    }
}
