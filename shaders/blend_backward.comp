#version 460
// Blend backward with float atomics. See include/blend_backward.glsl.
#extension GL_GOOGLE_include_directive : require
#define FLOAT_ATOMICS 1
#include "blend_backward.glsl"
