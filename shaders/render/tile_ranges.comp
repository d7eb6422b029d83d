#version 460
// Finds each tile's [start, end) in the tile-sorted entries: an entry starts its tile's range
// where its key differs from the previous one, and ends it where it differs from the next.
// Tiles with no entries keep the (0, 0) range the frame was cleared to.
//
// Each invocation takes ENTRIES_PER_INVOCATION consecutive keys in one 16-byte load (where the
// buffer is 16-byte aligned) and only their two neighbours singly: one key per invocation, with
// both neighbours read again, made this 4x its memory floor (lego tiled 5x5: 9.2 M entries).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference_uvec2 : require

#include "shaders/render/tile_binning.h"
#include "shaders/render/frame.h"

layout(local_size_x = 256) in;
const uint ENTRIES_PER_INVOCATION = TILE_RANGES_ENTRIES_PER_INVOCATION;

layout(push_constant) uniform Push { TileRangesPush pc; };

// Past either end of the entries: differs from every tile.
const uint NO_TILE = 0xffffffffu;

uint key_at(uint e, uint count) { return e < count ? pc.tile_keys.v[e] : NO_TILE; }

void main() {
    const uint count = pc.counters.v[COUNTER_ENTRIES];
    const uint tile_count = pc.tile_count;
    const bool aligned = (uvec2(pc.tile_keys).x & 15u) == 0u;
    for (uint q = gl_GlobalInvocationID.x; q * ENTRIES_PER_INVOCATION < count; q += gl_NumWorkGroups.x * gl_WorkGroupSize.x) {
        const uint first = q * ENTRIES_PER_INVOCATION;
        uint keys[ENTRIES_PER_INVOCATION + 2];  // the previous key, this invocation's, the next
        keys[0] = first == 0u ? NO_TILE : pc.tile_keys.v[first - 1u];
        if (aligned && first + ENTRIES_PER_INVOCATION <= count) {
            const uvec4 quad = UVec4s(pc.tile_keys).v[q];
            keys[1] = quad.x, keys[2] = quad.y, keys[3] = quad.z, keys[4] = quad.w;
        } else {
            for (uint i = 0u; i < ENTRIES_PER_INVOCATION; ++i) keys[1u + i] = key_at(first + i, count);
        }
        keys[ENTRIES_PER_INVOCATION + 1u] = key_at(first + ENTRIES_PER_INVOCATION, count);
        for (uint i = 0u; i < ENTRIES_PER_INVOCATION; ++i) {
            const uint tile = keys[1u + i];
            if (tile >= tile_count) continue;  // padding, or past the end
            if (keys[i] != tile) pc.ranges.v[tile].x = first + i;
            if (keys[i + 2u] != tile) pc.ranges.v[tile].y = first + i + 1u;
        }
    }
}
