#version 460
// Blend for training: the plain blend that also leaves each pixel's final transmittance and the
// end of its walked list for the backward pass. See include/blend_body.glsl.
#extension GL_GOOGLE_include_directive : require
#define GATHER_STATS 0
#define TRAIN_OUTPUTS 1
#include "blend_body.glsl"
