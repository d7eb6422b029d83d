// A drawn splat's footprint on screen, in one 32-byte record: everything emission and the blends
// read of a splat. They gather splats in depth order, so every splat is a random read, and each
// separate buffer (mean, conic and opacity, tile rectangle, tile count) cost one more memory
// sector per splat: lego tiled 5x5, 5.3 M splats, emission read four. Written by preprocess
// (drawn splats only); the colour buffer carries the depth beside the colour for the blends.
#ifndef VKSPLAT_RENDER_FOOTPRINT_H
#define VKSPLAT_RENDER_FOOTPRINT_H

#include "shaders/common/buffers.h"

SHADER_NAMESPACE_BEGIN(render)

struct Footprint {
    vec4 mean_conic;  // pixel position (x, y), conic a, b
    uvec4 rest;       // conic c and opacity as float bits, tile rectangle min and max as x | y << 16
};
BUFFER_REFERENCE(Footprints, Footprint, 16)

SHADER_NAMESPACE_END

#ifndef __cplusplus

Footprint make_footprint(vec2 mean, vec3 conic, float opacity, uvec2 lo, uvec2 hi) {
    return Footprint(vec4(mean, conic.xy),
                     uvec4(floatBitsToUint(conic.z), floatBitsToUint(opacity), lo.x | (lo.y << 16), hi.x | (hi.y << 16)));
}

vec2 footprint_mean(Footprint f) { return f.mean_conic.xy; }

// The conic (a, b, c) and the opacity.
vec4 footprint_conic_opacity(Footprint f) { return vec4(f.mean_conic.zw, uintBitsToFloat(f.rest.xy)); }

// Tiles [lo, hi) that its alpha >= 1/255 ellipse can meet (tile_culling.glsl).
void footprint_rect(Footprint f, out uvec2 lo, out uvec2 hi) {
    lo = uvec2(f.rest.z & 0xffffu, f.rest.z >> 16);
    hi = uvec2(f.rest.w & 0xffffu, f.rest.w >> 16);
}

#endif  // GLSL

#endif
