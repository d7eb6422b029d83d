#version 460
// Blend of one depth-ordered chunk of a frame, carrying each pixel's state to the next chunk
// (frames larger than the memory budget: Renderer::Impl::run_chunked, render/scene_chunks.*).
// See shaders/render/blend.h.
#extension GL_GOOGLE_include_directive : require
#define GATHER_STATS 0
#define CARRY_STATE 1
#include "shaders/render/blend.h"
layout(push_constant) uniform Push { BlendCarryPush pc; };
#include "shaders/render/blend_body.glsl"
