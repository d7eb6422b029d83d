#version 460
// Puts each visible splat's tile count in depth order, so that a scan over it hands out tile
// entry slots front to back: entries are then emitted already sorted by depth within every
// tile, and the tile sort only needs to be stable on the tile bits.
#extension GL_GOOGLE_include_directive : require

#include "buffers.glsl"
#include "frame.glsl"

layout(local_size_x = 256) in;

layout(push_constant) uniform Push {
    Uints counters;
    Uints depth_values;      // Gaussian indices in depth order
    Uints tiles_touched;     // per Gaussian
    Uints sorted_tile_counts;  // out: per visible splat, in depth order
} pc;

void main() {
    const uint count = pc.counters.v[COUNTER_VISIBLE];
    for (uint k = gl_GlobalInvocationID.x; k < count; k += gl_NumWorkGroups.x * gl_WorkGroupSize.x)
        pc.sorted_tile_counts.v[k] = pc.tiles_touched.v[pc.depth_values.v[k]];
}
