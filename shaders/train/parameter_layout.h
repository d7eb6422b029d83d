// Where a trainable scene's raw parameters (and, in the same layout, their gradients and Adam's
// moments) sit in one float array of N Gaussians with K SH coefficients per channel:
//   positions 3N | log-scales 3N | quaternions (w, x, y, z) 4N | opacity logits N | SH 3KN
// The SH block is [Gaussian][coefficient][rgb], the renderer's own layout, so the renderer's
// preprocess reads the trained SH in place. C++ reads it through train::ParameterLayout
// (src/train/parameter_layout.hpp). C++ names a constant kName, GLSL NAME.
#ifndef VKSPLAT_TRAIN_PARAMETER_LAYOUT_H
#define VKSPLAT_TRAIN_PARAMETER_LAYOUT_H

#include "shaders/common/shader_io.h"

#ifdef __cplusplus
#define TRAIN_CONST(glsl_name, cpp_name, value) inline constexpr uint cpp_name = value;
#else
#define TRAIN_CONST(glsl_name, cpp_name, value) const uint glsl_name = value;
#endif

SHADER_NAMESPACE_BEGIN(train)

// Each block starts at (floats per Gaussian before it) * N.
TRAIN_CONST(POSITIONS_AT, kPositionsAt, 0u)
TRAIN_CONST(LOG_SCALES_AT, kLogScalesAt, 3u)
TRAIN_CONST(ROTATIONS_AT, kRotationsAt, 6u)
TRAIN_CONST(OPACITIES_AT, kOpacitiesAt, 10u)
TRAIN_CONST(SH_AT, kShAt, 11u)

// Per-splat gradients the blend backward accumulates (floats per Gaussian): the projected mean
// (x, y, pixels), the conic (a, b, c), the opacity after the sigmoid and the colour (r, g, b).
TRAIN_CONST(SPLAT_GRAD_STRIDE, kSplatGradStride, 9u)
SHADER_CONST(uint, SPLAT_GRAD_MEAN, 0u)
SHADER_CONST(uint, SPLAT_GRAD_CONIC, 2u)
SHADER_CONST(uint, SPLAT_GRAD_OPACITY, 5u)
SHADER_CONST(uint, SPLAT_GRAD_COLOR, 6u)

// What densification decides by, per Gaussian (floats), summed over the steps since the last
// densification: the NDC gradient norm of its projected mean, the views it was drawn in, and the
// largest radius in pixels it had.
TRAIN_CONST(DENSIFY_STRIDE, kDensifyStride, 3u)
SHADER_CONST(uint, DENSIFY_GRAD_SUM, 0u)
SHADER_CONST(uint, DENSIFY_VIEWS, 1u)
SHADER_CONST(uint, DENSIFY_MAX_RADIUS, 2u)

// Bits of the step's status word (status[0]): why Adam skips this step.
TRAIN_CONST(STEP_NONFINITE, kStepNonfinite, 1u)    // some gradient was NaN or infinite
// The view needed more tile entries than the buffers hold, or a step before it did and has not
// been run again yet (the overflow mark): the host queues a step behind the one on the GPU, so a
// step recorded before its predecessor overflowed must change nothing either, and is run again
// after it.
TRAIN_CONST(STEP_OVERFLOWED, kStepOverflowed, 2u)
// With fixed-point sums (blend_backward_fixed.comp): a gradient the integers cannot hold (NaN,
// infinite or beyond SPLAT_GRAD_FIXED_LIMIT) reached some splat's totals. Which Gaussians it
// reached is lost with it, so no Gaussian steps; STEP_NONFINITE is set with it.
TRAIN_CONST(STEP_NONFINITE_SUMS, kStepNonfiniteSums, 4u)
// status[1], the overflow mark: set by a step whose frame overflowed, cleared only by the host when
// it records the step again (DifferentiableRenderer::record_backward's clear_overflow_mark).
TRAIN_CONST(STATUS_OVERFLOW_MARK, kStatusOverflowMark, 1u)
TRAIN_CONST(STATUS_WORDS, kStatusWords, 2u)

SHADER_NAMESPACE_END
#undef TRAIN_CONST

#ifndef __cplusplus
uint positions_offset(uint n) { return POSITIONS_AT * n; }
uint log_scales_offset(uint n) { return LOG_SCALES_AT * n; }
uint rotations_offset(uint n) { return ROTATIONS_AT * n; }
uint opacities_offset(uint n) { return OPACITIES_AT * n; }
uint sh_offset(uint n) { return SH_AT * n; }
#endif

#endif
