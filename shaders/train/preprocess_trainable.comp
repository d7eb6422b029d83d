#version 460
// Preprocess of the trainer's scene (render::TileBinning's, given by DifferentiableRenderer): its
// raw parameters (parameter_layout.h, laid out for the frame's Gaussian count), activated as they
// are read with the functions the host applies to a loaded scene (HostScene::activate), so a
// trained scene renders the same through either path: exp of the log-scales, sigmoid of the
// opacity logits, unit quaternions. preprocess_backward.comp differentiates them. Reading them
// here, rather than from an activated copy a pass of its own wrote, saves that copy (48 bytes a
// Gaussian) and the pass. See shaders/render/preprocess.glsl.
#extension GL_GOOGLE_include_directive : require
#include "shaders/common/buffers.h"
#include "shaders/train/differentiable_renderer.h"
#include "shaders/render/tile_binning.h"
#include "shaders/common/gaussian_shape.glsl"
layout(push_constant) uniform Push { PreprocessPush pc; };

float raw_parameter(uint k) { return Floats(pc.params).v[k]; }

vec4 gaussian_position_opacity(uint i) {
    const uint n = pc.camera.c.gaussian_count, p = positions_offset(n) + 3u * i;
    const float opacity = sigmoid(raw_parameter(opacities_offset(n) + i));
    return vec4(raw_parameter(p), raw_parameter(p + 1u), raw_parameter(p + 2u), opacity);
}

mat3 gaussian_covariance(uint i) {
    const uint n = pc.camera.c.gaussian_count;
    const uint s = log_scales_offset(n) + 3u * i, r = rotations_offset(n) + 4u * i;
    const vec3 scale = exp(vec3(raw_parameter(s), raw_parameter(s + 1u), raw_parameter(s + 2u)));
    const vec4 q = vec4(raw_parameter(r), raw_parameter(r + 1u), raw_parameter(r + 2u), raw_parameter(r + 3u));
    return covariance_3d(scale, q / length(q));
}
#define PREPROCESS_HOOKS 1
#include "shaders/render/preprocess.glsl"
