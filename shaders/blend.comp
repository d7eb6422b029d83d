#version 460
// Blend without statistics: what every plain render runs. See include/blend_body.glsl.
#extension GL_GOOGLE_include_directive : require
#define GATHER_STATS 0
#include "blend_body.glsl"
