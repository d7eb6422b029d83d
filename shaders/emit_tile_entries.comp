#version 460
// Emits one (tile, Gaussian) entry per tile each visible splat's rectangle covers, in depth
// order. Entries past the frame's capacity are dropped; the host sees COUNTER_ENTRIES_NEEDED
// exceed it, grows the buffers and renders the frame again.
#extension GL_GOOGLE_include_directive : require

#include "buffers.glsl"
#include "frame.glsl"

layout(local_size_x = 256) in;

layout(push_constant) uniform Push {
    CameraBuffer camera;
    Uints counters;
    Uints depth_values;   // Gaussian indices in depth order
    Uints entry_offsets;  // exclusive scan of the depth-ordered tile counts
    UVec2s rects;
    Uints tile_keys;      // out: tile index (row-major)
    Uints tile_values;    // out: Gaussian index
} pc;

void main() {
    const uint count = pc.counters.v[COUNTER_VISIBLE];
    const uint capacity = pc.camera.c.entry_capacity;
    const uint tiles_x = pc.camera.c.size.z;
    for (uint k = gl_GlobalInvocationID.x; k < count; k += gl_NumWorkGroups.x * gl_WorkGroupSize.x) {
        const uint gaussian = pc.depth_values.v[k];
        const uvec2 packed = pc.rects.v[gaussian];
        const uvec2 lo = uvec2(packed.x & 0xffffu, packed.x >> 16);
        const uvec2 hi = uvec2(packed.y & 0xffffu, packed.y >> 16);
        uint slot = pc.entry_offsets.v[k];
        for (uint y = lo.y; y < hi.y; ++y) {
            for (uint x = lo.x; x < hi.x; ++x) {
                if (slot >= capacity) return;
                pc.tile_keys.v[slot] = y * tiles_x + x;
                pc.tile_values.v[slot] = gaussian;
                ++slot;
            }
        }
    }
}
