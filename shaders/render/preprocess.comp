#version 460
// Preprocess of the renderer's scene: its activated parameters (GpuScene's layout), 3 vec4 per
// Gaussian. See shaders/render/preprocess.glsl.
#extension GL_GOOGLE_include_directive : require
#include "shaders/render/tile_binning.h"
#include "shaders/common/gaussian_shape.glsl"
layout(push_constant) uniform Push { PreprocessPush pc; };

vec4 gaussian_position_opacity(uint i) { return pc.params.v[3u * i]; }
mat3 gaussian_covariance(uint i) { return covariance_3d(pc.params.v[3u * i + 1u].xyz, pc.params.v[3u * i + 2u]); }
#define PREPROCESS_HOOKS 1
#include "shaders/render/preprocess.glsl"
