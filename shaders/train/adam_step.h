// adam_step.comp, recorded by src/train/trainer.cpp (the step's Adam update): one thread per
// float of the parameter array (shaders/train/parameter_layout.h), 256 per workgroup.
#ifndef VKSPLAT_TRAIN_ADAM_STEP_H
#define VKSPLAT_TRAIN_ADAM_STEP_H

#include "shaders/common/buffers.h"
#include "shaders/train/parameter_layout.h"

SHADER_NAMESPACE_BEGIN(train)

struct AdamStepPush {
    Floats params;
    Floats grads;
    Floats first_moment;
    Floats second_moment;
    Uints status;
    uint count;            // Gaussians
    uint sh_floats;        // SH floats per Gaussian (3 K)
    float lr_position, lr_scale, lr_rotation, lr_opacity, lr_sh_dc, lr_sh_rest;
    float beta1, beta2, epsilon;
    float bias_correction1;  // 1 - beta1^t
    float bias_correction2;  // 1 - beta2^t
    // 3DGS-MCMC's regularisers, added to the gradient here (0: off): d/d logit of
    // opacity_regularization x sigmoid(logit), and d/d log-scale of scale_regularization x exp(log-scale),
    // each weight already divided by the number of values the loss averages over.
    float opacity_regularization;
    float scale_regularization;
};

SHADER_NAMESPACE_END

#endif
