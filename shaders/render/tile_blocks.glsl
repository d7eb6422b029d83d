// How a blend workgroup walks its 16x16 tile, shared by the blend (blend_body.glsl) and its
// backward pass (blend_backward.glsl), which must visit the same pixels with the same splat masks.
#ifndef VKSPLAT_TILE_BLOCKS_GLSL
#define VKSPLAT_TILE_BLOCKS_GLSL

#include "vksplat/constants.hpp"
#include "shaders/render/tile_culling.glsl"

// The tile is walked as 8 blocks of 8x4 pixels, 32 consecutive invocations each (one warp on
// NVIDIA). When a splat enters shared memory, the thread that fetched it marks which blocks its
// alpha >= 1/255 ellipse meets (tile_culling.glsl), and each block's splats are listed
// (block_hit_lists.glsl): a pixel walks its block's list only. Most splats are a few pixels wide
// and touch one or two blocks, so most of a tile's evaluations go. Skipped splats have alpha
// < 1/255 there: pixels are unchanged.
const uvec2 BLOCK_SIZE = uvec2(8, 4);
const uint BLOCKS_ACROSS = TILE_WIDTH / BLOCK_SIZE.x;
const uint BLOCKS = TILE_WIDTH * TILE_HEIGHT / (BLOCK_SIZE.x * BLOCK_SIZE.y);

// The block holding an invocation's pixel.
uint block_of(uint invocation) { return invocation / (BLOCK_SIZE.x * BLOCK_SIZE.y); }

uvec2 pixel_in_tile(uint invocation) {
    const uint block = block_of(invocation);
    const uint within = invocation % (BLOCK_SIZE.x * BLOCK_SIZE.y);
    return uvec2(block % BLOCKS_ACROSS, block / BLOCKS_ACROSS) * BLOCK_SIZE +
           uvec2(within % BLOCK_SIZE.x, within / BLOCK_SIZE.x);
}

uint touched_blocks(vec2 mean, vec4 conic_opacity, uvec2 tile_origin) {
    const float bound = touch_bound(conic_opacity.w);
    uint mask = 0u;
    for (uint block = 0u; block < BLOCKS; ++block) {
        const uvec2 first = tile_origin + uvec2(block % BLOCKS_ACROSS, block / BLOCKS_ACROSS) * BLOCK_SIZE;
        if (ellipse_meets_box(mean, conic_opacity.xyz, bound, first, BLOCK_SIZE)) mask |= 1u << block;
    }
    return mask;
}

#endif
