#version 460
// Emits one (tile, Gaussian) entry per tile each visible splat can touch (tile_culling.glsl),
// in depth order. Entries past the frame's capacity are dropped; the host sees COUNTER_ENTRIES_NEEDED
// exceed it, grows the buffers and renders the frame again.
#extension GL_GOOGLE_include_directive : require

#include "buffers.glsl"
#include "frame.glsl"
#include "tile_culling.glsl"

layout(local_size_x = 256) in;

layout(push_constant) uniform Push {
    CameraBuffer camera;
    Uints counters;
    Uints depth_values;   // Gaussian indices in depth order
    Uints entry_offsets;  // exclusive scan of the depth-ordered tile counts
    UVec2s rects;
    Vec4s means_depth;
    Vec4s conic_opacity;
    Uints tiles_touched;
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
        const vec2 mean = pc.means_depth.v[gaussian].xy;
        const vec4 conic_o = pc.conic_opacity.v[gaussian];
        const float bound = touch_bound(conic_o.w);
        const uint first = pc.entry_offsets.v[k];
        const uint end = min(first + pc.tiles_touched.v[gaussian], capacity);
        uint slot = first;
        for (uint y = lo.y; y < hi.y && slot < end; ++y) {
            const uvec2 span = row_tile_span(mean, conic_o.xyz, bound, y, lo.x, hi.x);
            for (uint x = span.x; x < span.y && slot < end; ++x) {
                pc.tile_keys.v[slot] = y * tiles_x + x;
                pc.tile_values.v[slot] = gaussian;
                ++slot;
            }
        }
        for (; slot < end; ++slot) {
            pc.tile_keys.v[slot] = padding_tile(tiles_x * pc.camera.c.size.w);
            pc.tile_values.v[slot] = gaussian;
        }
    }
}
