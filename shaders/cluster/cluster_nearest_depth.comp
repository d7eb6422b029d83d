#version 460
// Cluster projection, step 1: a depth buffer of the nearest Gaussian centre per pixel. Each visible
// Gaussian whose centre lands in the image writes its view depth to the pixel holding the centre
// with atomicMin on the float bits (depths of visible splats are positive, so uint order is float
// order). The buffer starts at 0xffffffff (no centre).
#extension GL_GOOGLE_include_directive : require

#include "shaders/cluster/projection.h"

layout(local_size_x = 256) in;

layout(push_constant) uniform Push { ClusterNearestDepthPush pc; };

void main() {
    for (uint i = gl_GlobalInvocationID.x; i < pc.count; i += gl_NumWorkGroups.x * gl_WorkGroupSize.x) {
        const vec4 c = pc.centres.v[i];
        if (c.w <= 0.0) continue;
        const ivec2 pixel = ivec2(floor(c.xy + 0.5));
        if (any(lessThan(pixel, ivec2(0))) || pixel.x >= int(pc.width) || pixel.y >= int(pc.height)) continue;
        atomicMin(pc.nearest.v[uint(pixel.y) * pc.width + uint(pixel.x)], floatBitsToUint(c.z));
    }
}
