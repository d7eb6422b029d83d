#version 460
// Blend that also measures each Gaussian's contribution (RenderSettings::gather_stats).
// See include/blend_body.glsl.
#extension GL_GOOGLE_include_directive : require
#define GATHER_STATS 1
#include "blend_body.glsl"
