#version 460
// Blend without statistics: what every plain render runs. See shaders/render/blend.h.
#extension GL_GOOGLE_include_directive : require
#define GATHER_STATS 0
#include "shaders/render/blend.h"
layout(push_constant) uniform Push { BlendPush pc; };
#include "shaders/render/blend_body.glsl"
