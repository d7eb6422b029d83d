#version 460
#extension GL_GOOGLE_include_directive : require
// PrefixScan step 0 (one workgroup): reads the element count the GPU left at `count`, clamps it
// to the scratch capacity, writes the block count and the scan's indirect dispatch size (at
// least one workgroup, which writes the total of an empty scan) and clears the blocks'
// look-back words (see prefix_scan.cpp for the layout).
#include "shaders/sort/prefix_scan.h"

layout(local_size_x = 256) in;

layout(push_constant) uniform Push { ScanSetupPush pc; };

void main() {
    const uint count = min(pc.count.v[0], pc.capacity);
    const uint blocks = (count + pc.block - 1) / pc.block;
    for (uint b = gl_LocalInvocationIndex; b < blocks; b += gl_WorkGroupSize.x) pc.control.v[SCAN_LOOKBACK + b] = 0;
    if (gl_LocalInvocationIndex != 0) return;
    pc.control.v[0] = clamp(blocks, 1u, MAX_GROUPS_X);
    pc.control.v[1] = 1;
    pc.control.v[2] = 1;
    pc.control.v[3] = count;
    pc.control.v[4] = blocks;
}
