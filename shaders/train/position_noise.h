// position_noise.comp, recorded by src/train/trainer.cpp after Adam when TrainOptions::position_noise
// is on: one thread per Gaussian, 256 per workgroup.
#ifndef VKSPLAT_TRAIN_POSITION_NOISE_H
#define VKSPLAT_TRAIN_POSITION_NOISE_H

#include "shaders/common/buffers.h"
#include "shaders/train/parameter_layout.h"

SHADER_NAMESPACE_BEGIN(train)

struct PositionNoisePush {
    Floats params;
    Uints status;          // a skipped step (non-zero status) moves nothing either
    uint count;            // Gaussians
    uint seed;             // differs every step, so that every step draws new noise
    float scale;           // noise learning rate x the step's position learning rate
};

SHADER_NAMESPACE_END

#endif
