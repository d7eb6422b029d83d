#version 460
// Blend that also measures each Gaussian's contribution (RenderSettings::gather_stats).
// See shaders/render/blend.h.
#extension GL_GOOGLE_include_directive : require
#define GATHER_STATS 1
#include "shaders/render/blend.h"
layout(push_constant) uniform Push { BlendStatsPush pc; };
#include "shaders/render/blend_body.glsl"
