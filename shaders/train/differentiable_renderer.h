// The training passes of a view, recorded by src/train/differentiable_renderer.cpp
// (DifferentiableRenderer): the render passes with preprocess_trainable.comp (whose push is
// render's PreprocessPush, shaders/render/tile_binning.h) and blend_train.comp (render's
// BlendTrainPush, shaders/render/blend.h), then blend_backward.comp (or
// blend_backward_cas.comp, their per-splat forms blend_backward_per_splat.comp and
// blend_backward_per_splat_cas.comp) and preprocess_backward.comp, or blend_backward_fixed.comp and
// preprocess_backward_fixed.comp; then sh_backward.comp.
#ifndef VKSPLAT_TRAIN_DIFFERENTIABLE_RENDERER_H
#define VKSPLAT_TRAIN_DIFFERENTIABLE_RENDERER_H

#include "shaders/common/buffers.h"
#include "shaders/render/footprint.h"
#include "shaders/render/frame.h"
#include "shaders/train/adam_step.h"
#include "shaders/train/parameter_layout.h"
#ifdef __cplusplus
#include "shaders/render/blend.h"  // BlendTrainPush (GLSL: blend_train.comp includes it with its flags)
#include "shaders/render/tile_binning.h"  // PreprocessPush (GLSL: preprocess_trainable.comp includes it)
#endif

SHADER_NAMESPACE_BEGIN(train)

#ifdef __cplusplus
using render::BlendTrainPush;
using render::PreprocessPush;
using render::CameraBuffer;
using render::Footprints;
#endif

// blend_backward.comp, blend_backward_cas.comp, blend_backward_fixed.comp (whose splat_grads
// holds Int64s), blend_backward_per_splat.comp, blend_backward_per_splat_cas.comp: one workgroup
// per tile.
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
    Uints status;          // the step's status: fixed-point sums set STEP_NONFINITE_SUMS there
};

// Deterministic sums (--deterministic): blend_backward_fixed.comp adds each splat's gradients as
// 64-bit integers, SPLAT_GRAD_FIXED_SCALE units per 1.0 (2^40: steps of 9.1e-13, totals within
// +-8.4e6), because integer addition gives the same total in any order where float addition does
// not; preprocess_backward_fixed.comp reads the totals. 64-bit integer types exist in GLSL only
// with their extension, so only these two shaders declare them.
SHADER_CONST(float, SPLAT_GRAD_FIXED_SCALE, 1099511627776.0)
SHADER_CONST(float, SPLAT_GRAD_FIXED_LIMIT, 8.0e6)  // below 2^63 / SPLAT_GRAD_FIXED_SCALE
#if !defined(__cplusplus) && FIXED_POINT_SUMS
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
layout(buffer_reference, std430, buffer_reference_align = 8) buffer Int64s { int64_t v[]; };
#endif

// preprocess_backward.comp, preprocess_backward_fixed.comp (whose splat_grads holds Int64s): one
// thread per Gaussian, 256 per workgroup.
struct PreprocessBackwardPush {
    CameraBuffer camera;
    Floats raw;          // parameters, shaders/train/parameter_layout.h
    Uints tiles_touched; // per Gaussian: 0 where the frame did not draw it
    Floats splat_grads;  // SPLAT_GRAD_STRIDE per Gaussian
    Floats grads;        // out, where `adam` is 0: gradients of `raw`, same layout
    Uints counters;      // the frame's counters
    Uints status;        // [0]: STEP_ bits, [STATUS_OVERFLOW_MARK]: the overflow mark
    Floats densify;      // DENSIFY_STRIDE per Gaussian: what densification decides by
    Vec4s means_depth;   // the frame's projected splats: w is the radius in pixels
    // out, 2 per Gaussian: its view direction (w: 1 where its SH steps, 0 where its gradient was
    // not finite) and d L / d colour, for sh_backward.comp
    Vec4s sh_steps;
    // A training step's Adam settings (adam_step.h): the pass steps `raw` by its gradients instead
    // of writing them to `grads`. 0: write them (gradient checks, Fisher probes).
    OPTIONAL_ADDRESS(AdamSettingsBuffer) adam;
};

// sh_backward.comp: one thread per SH float, four at a time, 256 per workgroup.
struct ShBackwardPush {
    CameraBuffer camera;
    Floats raw;
    Floats grads;        // out, where `adam` is 0
    Uints counters;
    Uints status;
    Vec4s sh_steps;      // what preprocess_backward.comp left
    OPTIONAL_ADDRESS(AdamSettingsBuffer) adam;
};

SHADER_NAMESPACE_END

#endif
