#version 460
// After a blend: what removing each Gaussian alone would change in the picture
// (RenderSettings::gather_removal_error). See include/blend_body.glsl.
#extension GL_GOOGLE_include_directive : require
#define GATHER_STATS 0
#define REMOVAL_ERROR 1
#include "blend_body.glsl"
