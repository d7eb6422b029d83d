#version 460
#extension GL_GOOGLE_include_directive : require
// RadixSort step 0 (one invocation, once per sort): reads the key count the GPU left at `count`,
// clamps it to what the buffers hold and writes the block count and the indirect dispatch size
// of the per-block kernels into the control words (layout in radix_sort.cpp).
#include "buffers.glsl"

layout(local_size_x = 1) in;

layout(push_constant) uniform Push {
    Uints count;
    Uints control;  // [0..2] DispatchArgs, [3] count, [4] blocks
    uint capacity;
    uint block;     // keys per block
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
