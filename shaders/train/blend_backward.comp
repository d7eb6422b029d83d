#version 460
// Blend backward with float atomics. See shaders/train/blend_backward.glsl.
#extension GL_GOOGLE_include_directive : require
#define FLOAT_ATOMICS 1
#define FIXED_POINT_SUMS 0
#define PER_SPLAT 0
#include "shaders/train/differentiable_renderer.h"
layout(push_constant) uniform Push { BlendBackwardPush pc; };
#include "shaders/train/blend_backward.glsl"
