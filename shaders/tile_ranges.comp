#version 460
// Finds each tile's [start, end) in the tile-sorted entries: an entry starts its tile's range
// where its key differs from the previous one, and ends it where it differs from the next.
// Tiles with no entries keep the (0, 0) range the frame was cleared to.
#extension GL_GOOGLE_include_directive : require

#include "buffers.glsl"
#include "frame.glsl"

layout(local_size_x = 256) in;

layout(push_constant) uniform Push {
    Uints counters;
    Uints tile_keys;
    UVec2s ranges;  // out: per tile
    uint tile_count;  // keys at or past it are padding (tile_culling.glsl) and have no range
} pc;

void main() {
    const uint count = pc.counters.v[COUNTER_ENTRIES];
    const uint tile_count = pc.tile_count;
    for (uint e = gl_GlobalInvocationID.x; e < count; e += gl_NumWorkGroups.x * gl_WorkGroupSize.x) {
        const uint tile = pc.tile_keys.v[e];
        if (tile >= tile_count) continue;
        if (e == 0u || pc.tile_keys.v[e - 1u] != tile) pc.ranges.v[tile].x = e;
        if (e + 1u == count || pc.tile_keys.v[e + 1u] != tile) pc.ranges.v[tile].y = e + 1u;
    }
}
