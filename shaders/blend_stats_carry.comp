#version 460
// Blend of one depth-ordered chunk that also measures each Gaussian's contribution (statistics
// of a frame larger than the memory budget). See include/blend_body.glsl.
#extension GL_GOOGLE_include_directive : require
#define GATHER_STATS 1
#define CARRY_STATE 1
#include "blend_body.glsl"
