// The training loss's kernel (loss.comp), recorded by src/train/loss_passes.cpp (LossPasses):
// one workgroup per channel of a strip of LOSS_SEGMENT_TILES tiles, one above the other.
#ifndef VKSPLAT_TRAIN_LOSS_H
#define VKSPLAT_TRAIN_LOSS_H

#include "shaders/common/buffers.h"

SHADER_NAMESPACE_BEGIN(train)

// A tile's pixels = the workgroup's invocations: the host sizes the dispatch by them.
SHADER_CONST(uint, LOSS_TILE_WIDTH, 32)
SHADER_CONST(uint, LOSS_TILE_HEIGHT, 8)
// Tiles per strip. Longer strips compute the 10 rows above each strip (which the strip above
// computes too) less often, shorter ones make more workgroups for small images.
SHADER_CONST(uint, LOSS_SEGMENT_TILES, 8)

struct LossPush {
    Vec4s rendered;     // rgb, alpha unused
    Uints photo;        // RGBA8, r in the low byte; alpha 0 masks the pixel out
    Vec4s partials;     // out: per workgroup the sums of |x - y|, SSIM, (x - y)^2 (w = 0)
    Vec4s gradient;     // out: dL/d rgb, w = 0
    uint width;
    uint height;
    uint tiles_x;       // tiles per row of the image
    uint tiles_y;       // tiles per column
    uint strips;        // tiles_x * ceil(tiles_y / LOSS_SEGMENT_TILES)
    float ssim_weight;  // lambda
    float inv_count;    // 1 / (3 * width * height): every mean divides by all pixels and channels
};

SHADER_NAMESPACE_END

#endif
