#version 460
// Blend of one depth-ordered chunk that also measures each Gaussian's contribution (statistics
// of a frame larger than the memory budget). See shaders/render/blend.h.
#extension GL_GOOGLE_include_directive : require
#define GATHER_STATS 1
#define CARRY_STATE 1
#include "shaders/render/blend.h"
layout(push_constant) uniform Push { BlendStatsCarryPush pc; };
#include "shaders/render/blend_body.glsl"
