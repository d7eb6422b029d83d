#version 460
// Emits one (tile, Gaussian) entry per tile each visible splat can touch (tile_culling.glsl),
// in depth order. Entries past the frame's capacity are dropped; the host sees COUNTER_ENTRIES_NEEDED
// exceed it, grows the buffers and renders the frame again.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require

#include "shaders/render/tile_binning.h"
#include "shaders/render/footprint.h"
#include "shaders/render/frame.h"
#include "shaders/render/tile_culling.glsl"

layout(local_size_x = 256) in;

layout(push_constant) uniform Push { EmitTileEntriesPush pc; };

// Where splat k of the depth order has its entries: its Gaussian, footprint and positions
// [first, end), end clamped to the frame's capacity. The end is the next splat's start (read in
// order, where the splat's own tile count would be one more random read).
struct SplatEntries {
    uint gaussian;
    Footprint footprint;
    uint first, end;
};

SplatEntries splat_entries(uint k, uint count, uint capacity) {
    const uint gaussian = pc.depth_values.v[k];
    const uint end = k + 1u < count ? pc.entry_offsets.v[k + 1u] : pc.counters.v[COUNTER_ENTRIES_NEEDED];
    return SplatEntries(gaussian, pc.footprints.v[gaussian], pc.entry_offsets.v[k], min(end, capacity));
}

// Writes the splat's entries from position first on, row by row and left to right in each row,
// and returns the position after them. `row_step` invocations take consecutive rows together:
// 1 for one invocation alone, gl_SubgroupSize for a whole subgroup (then it is called in uniform
// control flow with the same splat, and `lane` is gl_SubgroupInvocationID).
uint emit_rows(SplatEntries e, uint tiles_x, uint lane, uint row_step) {
    const uint gaussian = e.gaussian;
    const vec2 mean = footprint_mean(e.footprint);
    const vec4 conic_o = footprint_conic_opacity(e.footprint);
    const float bound = touch_bound(conic_o.w);
    uvec2 lo, hi;
    footprint_rect(e.footprint, lo, hi);
    uint slot = e.first;
    for (uint row0 = lo.y; row0 < hi.y && slot < e.end; row0 += row_step) {
        const uint y = row0 + lane;
        const uvec2 span = y < hi.y ? row_tile_span(mean, conic_o.xyz, bound, y, lo.x, hi.x) : uvec2(0u);
        const uint tiles = span.y - span.x;
        uint at = slot + (row_step == 1u ? 0u : subgroupExclusiveAdd(tiles));
        for (uint x = span.x; x < span.y && at < e.end; ++x, ++at) {
            pc.tile_keys.v[at] = y * tiles_x + x;
            pc.tile_values.v[at] = gaussian;
        }
        slot += row_step == 1u ? tiles : subgroupAdd(tiles);
    }
    return slot;
}

// Splats with more tiles than this are emitted by their whole subgroup, a row per invocation: one
// invocation writing a huge splat's thousands of entries alone held up the pass (snowmiku).
const uint SHARED_EMIT_TILES = 128;

void main() {
    const uint count = pc.counters.v[COUNTER_VISIBLE];
    const uint capacity = pc.camera.c.entry_capacity;
    const uint tiles_x = pc.camera.c.size.z;
    const uint padding = padding_tile(tiles_x * pc.camera.c.size.w);
    const uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    // Every invocation of a subgroup makes the same trips (the base is uniform), so that the
    // subgroup can share the large splats' work.
    for (uint base = gl_WorkGroupID.x * gl_WorkGroupSize.x; base < count; base += stride) {
        const uint k = base + gl_LocalInvocationIndex;
        SplatEntries e = SplatEntries(0u, Footprint(vec4(0.0), uvec4(0u)), 0u, 0u);
        if (k < count) e = splat_entries(k, count, capacity);
        const bool large = e.end > e.first + SHARED_EMIT_TILES;
        uint slot = e.first;
        if (k < count && !large) slot = emit_rows(e, tiles_x, 0u, 1u);
        // The large splats, in depth order, each by the whole subgroup.
        bool waiting = large;
        while (subgroupBallotBitCount(subgroupBallot(waiting)) != 0u) {
            const uint next = subgroupMin(waiting ? k : 0xffffffffu);
            const uint emitted = emit_rows(splat_entries(next, count, capacity), tiles_x, gl_SubgroupInvocationID, gl_SubgroupSize);
            if (waiting && k == next) {
                slot = emitted;
                waiting = false;
            }
        }
        for (; slot < e.end; ++slot) {
            pc.tile_keys.v[slot] = padding;
            pc.tile_values.v[slot] = e.gaussian;
        }
    }
}
