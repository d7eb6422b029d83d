// The training passes of a view, recorded by src/train/differentiable_renderer.cpp
// (DifferentiableRenderer): train_activate.comp, then the render passes and blend_train.comp
// (whose push is render's BlendTrainPush, shaders/render/blend.h), then blend_backward.comp (or
// blend_backward_cas.comp) and preprocess_backward.comp.
#ifndef VKSPLAT_TRAIN_DIFFERENTIABLE_RENDERER_H
#define VKSPLAT_TRAIN_DIFFERENTIABLE_RENDERER_H

#include "shaders/common/buffers.h"
#include "shaders/render/footprint.h"
#include "shaders/render/frame.h"
#include "shaders/train/parameter_layout.h"
#ifdef __cplusplus
#include "shaders/render/blend.h"  // BlendTrainPush (GLSL: blend_train.comp includes it with its flags)
#endif

SHADER_NAMESPACE_BEGIN(train)

#ifdef __cplusplus
using render::BlendTrainPush;
using render::CameraBuffer;
using render::Footprints;
#endif

// train_activate.comp: the raw parameters into the renderer's activated ones, 256 Gaussians per workgroup.
struct TrainActivatePush {
    Floats raw;
    Vec4s params;  // out: 3 vec4 per Gaussian
    uint count;
};

// blend_backward.comp, blend_backward_cas.comp: one workgroup per tile.
struct BlendBackwardPush {
    CameraBuffer camera;
    UVec2s ranges;
    Uints tile_values;
    Footprints footprints;
    Vec4s colors;          // rgb and view depth
    Floats transmittance;  // per pixel: final T (blend_train.comp)
    Uints last;            // per pixel: one past the last list position it blended
    Vec4s pixel_grad;      // per pixel: dL / d rgb
    Floats splat_grads;    // out, accumulated: SPLAT_GRAD_STRIDE per Gaussian
};

// preprocess_backward.comp: one thread per Gaussian, 256 per workgroup.
struct PreprocessBackwardPush {
    CameraBuffer camera;
    Floats raw;          // parameters, shaders/train/parameter_layout.h
    Uints tiles_touched; // per Gaussian: 0 where the frame did not draw it
    Floats splat_grads;  // SPLAT_GRAD_STRIDE per Gaussian
    Floats grads;        // out: gradients of `raw`, same layout
    Uints counters;      // the frame's counters
    Uints status;        // [0]: STEP_ bits
    Floats densify;      // DENSIFY_STRIDE per Gaussian: what densification decides by
    Vec4s means_depth;   // the frame's projected splats: w is the radius in pixels
};

SHADER_NAMESPACE_END

#endif
