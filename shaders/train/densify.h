// The densification kernels, recorded by src/train/densify.cpp (DensifyPasses):
// densify_gather.comp and reset_opacity.comp, 256 Gaussians per workgroup.
#ifndef VKSPLAT_TRAIN_DENSIFY_H
#define VKSPLAT_TRAIN_DENSIFY_H

#include "shaders/common/buffers.h"
#include "shaders/train/parameter_layout.h"

SHADER_NAMESPACE_BEGIN(train)

// densify_gather.comp: one new array (parameters or a moment) from the old one of that kind.
struct DensifyGatherPush {
    Floats old_values;
    Floats new_values;
    Uints sources;         // per new Gaussian: the old one it copies
    Floats overrides;      // per overridden Gaussian: position (3), log-scale (3), opacity logit (1)
    uint old_count;
    uint new_count;
    uint zero_from;        // Gaussians from here on get zeros (new Gaussians' moments); new_count: none
    uint override_from;    // Gaussians with values of their own (overrides) from here on; new_count: none
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
