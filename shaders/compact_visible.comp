#version 460
// Compaction: writes the visible splats' depth keys and Gaussian indices in index order, at the
// positions an exclusive scan of the visibility flags gave them. Index order (rather than an
// atomic counter) makes the depth sort's ties fall the way the reference's do, and every frame
// bit-identical.
#extension GL_GOOGLE_include_directive : require

#include "buffers.glsl"
#include "frame.glsl"

layout(local_size_x = 256) in;

layout(push_constant) uniform Push {
    CameraBuffer camera;
    Uints visible;
    Uints offsets;        // exclusive scan of visible
    Vec4s means_depth;
    Uints depth_keys;     // out: view depth as float bits (depth > 0, so they sort as uints)
    Uints depth_values;   // out: Gaussian index
} pc;

void main() {
    const uint count = pc.camera.c.gaussian_count;
    for (uint i = gl_GlobalInvocationID.x; i < count; i += gl_NumWorkGroups.x * gl_WorkGroupSize.x) {
        if (pc.visible.v[i] == 0u) continue;
        const uint slot = pc.offsets.v[i];
        pc.depth_keys.v[slot] = floatBitsToUint(pc.means_depth.v[i].z);
        pc.depth_values.v[slot] = i;
    }
}
