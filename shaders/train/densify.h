// The densification kernels, recorded by src/train/densify.cpp (DensifyPasses):
// densify_gather.comp and reset_opacity.comp, 256 Gaussians per workgroup.
#ifndef VKSPLAT_TRAIN_DENSIFY_H
#define VKSPLAT_TRAIN_DENSIFY_H

#include "shaders/common/buffers.h"
#include "shaders/train/parameter_layout.h"

SHADER_NAMESPACE_BEGIN(train)

// densify_gather.comp: the new parameter array and moments from the old ones.
struct DensifyGatherPush {
    Floats old_params;
    Floats old_first;
    Floats old_second;
    Floats new_params;
    Floats new_first;
    Floats new_second;
    Uints sources;         // per new Gaussian: the old one it copies
    Floats overrides;      // per overridden Gaussian: position (3), log-scale (3), opacity logit (1)
    uint old_count;
    uint new_count;
    uint fresh_from;       // new Gaussians (zero moments) from here on
    uint override_from;    // Gaussians with values of their own (overrides) from here on
    uint sh_floats;        // SH floats per Gaussian (3 K)
};

// reset_opacity.comp: opacities clamped to max_logit, their moments zeroed.
struct ResetOpacityPush {
    Floats params;
    Floats first_moment;
    Floats second_moment;
    uint count;
    float max_logit;
};

SHADER_NAMESPACE_END

#endif
