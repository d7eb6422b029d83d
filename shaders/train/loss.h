// The training loss's kernel (loss.comp), recorded by src/train/loss_passes.cpp (LossPasses):
// one workgroup per 16 x 16 tile.
#ifndef VKSPLAT_TRAIN_LOSS_H
#define VKSPLAT_TRAIN_LOSS_H

#include "shaders/common/buffers.h"

SHADER_NAMESPACE_BEGIN(train)

SHADER_CONST(uint, LOSS_TILE, 16)  // pixels per tile side = workgroup side: the host sizes the dispatch by it

struct LossPush {
    Vec4s rendered;     // rgb, alpha unused
    Uints photo;        // RGBA8, r in the low byte; alpha 0 masks the pixel out
    Vec4s partials;     // out: per workgroup the sums of |x - y|, SSIM, (x - y)^2 (w = 0)
    Vec4s gradient;     // out: dL/d rgb, w = 0
    uint width;
    uint height;
    uint tiles_x;
    uint tiles;
    float ssim_weight;  // lambda
    float inv_count;    // 1 / (3 * width * height): every mean divides by all pixels and channels
};

SHADER_NAMESPACE_END

#endif
