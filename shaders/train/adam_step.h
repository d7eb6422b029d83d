// Adam's settings for one training step, which preprocess_backward.comp and sh_backward.comp read
// through their pushes' `adam` to step each Gaussian's parameters as it finds their gradients
// (shaders/train/adam.glsl). The trainer (src/train/trainer.cpp) writes them into a small device
// buffer at the start of each step's commands: they change every step (bias corrections, decaying
// rates) and do not fit the push constants' 128 bytes beside the pass's own addresses.
#ifndef VKSPLAT_TRAIN_ADAM_STEP_H
#define VKSPLAT_TRAIN_ADAM_STEP_H

#include "shaders/common/buffers.h"

SHADER_NAMESPACE_BEGIN(train)

struct AdamSettings {
    Floats first_moment;   // laid out as the parameters (parameter_layout.h)
    Floats second_moment;
    float lr_position, lr_scale, lr_rotation, lr_opacity, lr_sh_dc, lr_sh_rest;
    float beta1, beta2, epsilon;
    float bias_correction1;  // 1 - beta1^t
    float bias_correction2;  // 1 - beta2^t
    // 3DGS-MCMC's regularisers, added to the gradient (0: off): d/d logit of
    // opacity_regularization x sigmoid(logit), and d/d log-scale of scale_regularization x exp(log-scale),
    // each weight already divided by the number of values the loss averages over.
    float opacity_regularization;
    float scale_regularization;
};

SHADER_NAMESPACE_END

#ifdef __cplusplus
SHADER_NAMESPACE_BEGIN(train)
BUFFER_REFERENCE(AdamSettingsBuffer, AdamSettings, 8)
// std430's layout of the GLSL struct: two 8-byte addresses, 13 floats, padded to 8 bytes.
static_assert(sizeof(AdamSettings) == 72 && offsetof(AdamSettings, lr_position) == 16);
SHADER_NAMESPACE_END
#else
layout(buffer_reference, std430, buffer_reference_align = 8) readonly buffer AdamSettingsBuffer { AdamSettings s; };
#endif

#endif
