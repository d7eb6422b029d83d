#version 460
// Blend backward for devices without float atomics. See include/blend_backward.glsl.
#extension GL_GOOGLE_include_directive : require
#define FLOAT_ATOMICS 0
#include "blend_backward.glsl"
