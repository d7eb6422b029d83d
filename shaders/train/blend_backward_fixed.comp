#version 460
// Blend backward with 64-bit integer sums, the same bytes in any order (train --deterministic).
// See shaders/train/blend_backward.glsl.
#extension GL_GOOGLE_include_directive : require
#define FLOAT_ATOMICS 0
#define FIXED_POINT_SUMS 1
#define PER_SPLAT 0
#include "shaders/train/differentiable_renderer.h"
layout(push_constant) uniform Push { BlendBackwardPush pc; };
#include "shaders/train/blend_backward.glsl"
