#version 460
// Preprocess backward where the blend backward summed its gradients as floats.
// See shaders/train/preprocess_backward.glsl.
#extension GL_GOOGLE_include_directive : require
#define FIXED_POINT_SUMS 0
#include "shaders/train/differentiable_renderer.h"
layout(push_constant) uniform Push { PreprocessBackwardPush pc; };
#include "shaders/train/preprocess_backward.glsl"
