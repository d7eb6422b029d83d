#version 460
// Activation: the trainer's raw parameters (parameter_layout.h) to the renderer's activated
// params (GpuScene): exp of the log-scales, sigmoid of the opacity logits, unit quaternions. The
// same functions the host applies to a loaded scene (HostScene::activate), so a trained scene
// renders the same through either path. preprocess_backward.comp differentiates them.
#extension GL_GOOGLE_include_directive : require

#include "shaders/common/buffers.h"
#include "shaders/train/differentiable_renderer.h"

layout(local_size_x = 256) in;

layout(push_constant) uniform Push { TrainActivatePush pc; };

void main() {
    const uint n = pc.count;
    for (uint i = gl_GlobalInvocationID.x; i < n; i += gl_NumWorkGroups.x * gl_WorkGroupSize.x) {
        const uint p = positions_offset(n) + 3u * i, s = log_scales_offset(n) + 3u * i;
        const uint r = rotations_offset(n) + 4u * i;
        const vec3 position = vec3(pc.raw.v[p], pc.raw.v[p + 1u], pc.raw.v[p + 2u]);
        const vec3 scale = exp(vec3(pc.raw.v[s], pc.raw.v[s + 1u], pc.raw.v[s + 2u]));
        const vec4 q = vec4(pc.raw.v[r], pc.raw.v[r + 1u], pc.raw.v[r + 2u], pc.raw.v[r + 3u]);
        const float opacity = 1.0 / (1.0 + exp(-pc.raw.v[opacities_offset(n) + i]));
        pc.params.v[3u * i] = vec4(position, opacity);
        pc.params.v[3u * i + 1u] = vec4(scale, 0.0);
        pc.params.v[3u * i + 2u] = q / length(q);
    }
}
