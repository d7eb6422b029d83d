#version 460
#extension GL_GOOGLE_include_directive : require
// PrefixScan step 0 (one invocation): reads the element count the GPU left at `count`, clamps it
// to the scratch capacity and writes the block count and the indirect dispatch size for the
// per-block kernels into the scratch's control words (see prefix_scan.cpp for the layout).
#include "buffers.glsl"

layout(local_size_x = 1) in;

layout(push_constant) uniform Push {
    Uints count;     // one uint: number of elements
    Uints control;   // scratch: [0..2] DispatchArgs, [3] count, [4] blocks, [16..] block sums
    uint capacity;   // scratch capacity in elements
    uint block;      // elements per block
} pc;

void main() {
    const uint count = min(pc.count.v[0], pc.capacity);
    const uint blocks = (count + pc.block - 1) / pc.block;
    pc.control.v[0] = min(blocks, MAX_GROUPS_X);
    pc.control.v[1] = 1;
    pc.control.v[2] = 1;
    pc.control.v[3] = count;
    pc.control.v[4] = blocks;
}
