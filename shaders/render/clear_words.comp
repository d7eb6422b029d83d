#version 460
// Sets `count` words to `value`. A buffer clear as a kernel runs beside the kernel after the same
// barrier; vkCmdFillBuffer at a frame's start added about 2-3 us to the frame's chain on an H200
// (small vkCmdUpdateBuffer uploads did not).
#extension GL_GOOGLE_include_directive : require

#include "shaders/render/tile_binning.h"

layout(local_size_x = 256) in;

layout(push_constant) uniform Push { ClearWordsPush pc; };

void main() {
    for (uint i = gl_GlobalInvocationID.x; i < pc.count; i += gl_NumWorkGroups.x * gl_WorkGroupSize.x)
        pc.words.v[i] = pc.value;
}
