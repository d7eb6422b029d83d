#version 460
// Copies 16-byte words with every invocation of the device: the memory-bandwidth probe behind the
// benchmark's floor. A shader copy, not vkCmdCopyBuffer, because the renderer's passes move their
// bytes through shader cores too, and some drivers run buffer copies on a slower copy engine.
#extension GL_GOOGLE_include_directive : require

#include "shaders/bench/bandwidth_copy.h"

layout(local_size_x = 256) in;

layout(push_constant) uniform Push { BandwidthCopyPush pc; };

void main() {
    for (uint i = gl_GlobalInvocationID.x; i < pc.count; i += gl_NumWorkGroups.x * gl_WorkGroupSize.x)
        pc.target.v[i] = pc.source.v[i];
}
