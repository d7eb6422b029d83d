#version 460
// Preprocess backward where the blend backward summed its gradients as 64-bit integers
// (blend_backward_fixed.comp).
// See shaders/train/preprocess_backward.glsl.
#extension GL_GOOGLE_include_directive : require
#define FIXED_POINT_SUMS 1
#include "shaders/train/differentiable_renderer.h"
layout(push_constant) uniform Push { PreprocessBackwardPush pc; };
#include "shaders/train/preprocess_backward.glsl"
