#version 460
// Blend for training: the plain blend that also leaves each pixel's final transmittance and the
// end of its walked list for the backward pass. See shaders/render/blend.h.
#extension GL_GOOGLE_include_directive : require
#define GATHER_STATS 0
#define TRAIN_OUTPUTS 1
#include "shaders/render/blend.h"
#include "shaders/train/differentiable_renderer.h"
layout(push_constant) uniform Push { BlendTrainPush pc; };
#include "shaders/render/blend_body.glsl"
