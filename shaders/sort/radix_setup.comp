#version 460
#extension GL_GOOGLE_include_directive : require
// RadixSort step 0 (one workgroup, once per sort): reads the key count the GPU left at `count`,
// clamps it to what the buffers hold, writes the block count and the indirect dispatch size of
// the per-block kernels into the control words (layout in radix_sort.cpp), and clears the
// per-pass digit totals that the histogram kernel adds to (a kernel instead of a buffer fill so
// that the clear needs no barrier of its own).
#include "shaders/sort/radix_sort.h"

layout(local_size_x = 256) in;

layout(push_constant) uniform Push { RadixSetupPush pc; };

void main() {
    for (uint i = gl_LocalInvocationIndex; i < MAX_PASSES * RADIX_MAX; i += gl_WorkGroupSize.x)
        pc.control.v[RADIX_TOTALS + i] = 0;
    if (gl_LocalInvocationIndex != 0) return;
    const uint count = min(pc.count.v[0], pc.capacity);
    const uint blocks = (count + pc.block - 1) / pc.block;
    pc.control.v[0] = min(blocks, MAX_GROUPS_X);
    pc.control.v[1] = 1;
    pc.control.v[2] = 1;
    pc.control.v[3] = count;
    pc.control.v[4] = blocks;
}
