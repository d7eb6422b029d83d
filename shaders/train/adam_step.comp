#version 460
// Adam (Kingma & Ba), as torch.optim.Adam steps the reference trainer's parameter groups: one
// thread per parameter float, with the learning rate of its group (parameter_layout.h's blocks;
// the SH block splits into the DC coefficient and the rest). Every parameter steps every
// iteration, also with a zero gradient (the moments decay), as torch's dense Adam does. A step
// whose status says a gradient was not finite, or the frame overflowed its tile entries, changes
// nothing: the host counts it as skipped. The regularisers of TrainOptions (3DGS-MCMC's mean opacity
// and mean scale terms) join the gradient here: they reach every Gaussian, seen or not.
#extension GL_GOOGLE_include_directive : require

#include "shaders/common/buffers.h"
#include "shaders/train/adam_step.h"

layout(local_size_x = 256) in;

layout(push_constant) uniform Push { AdamStepPush pc; };

float learning_rate(uint index, uint n) {
    if (index < log_scales_offset(n)) return pc.lr_position;
    if (index < rotations_offset(n)) return pc.lr_scale;
    if (index < opacities_offset(n)) return pc.lr_rotation;
    if (index < sh_offset(n)) return pc.lr_opacity;
    return (index - sh_offset(n)) % pc.sh_floats < 3u ? pc.lr_sh_dc : pc.lr_sh_rest;
}

void main() {
    if (pc.status.v[0] != 0u) return;
    const uint n = pc.count;
    const uint total = sh_offset(n) + pc.sh_floats * n;
    for (uint i = gl_GlobalInvocationID.x; i < total; i += gl_NumWorkGroups.x * gl_WorkGroupSize.x) {
        float g = pc.grads.v[i];
        if (i >= opacities_offset(n) && i < sh_offset(n)) {
            const float opacity = 1.0 / (1.0 + exp(-pc.params.v[i]));
            g += pc.opacity_regularization * opacity * (1.0 - opacity);
        } else if (i >= log_scales_offset(n) && i < rotations_offset(n)) {
            g += pc.scale_regularization * exp(pc.params.v[i]);
        }
        const float m = pc.beta1 * pc.first_moment.v[i] + (1.0 - pc.beta1) * g;
        const float v = pc.beta2 * pc.second_moment.v[i] + (1.0 - pc.beta2) * g * g;
        pc.first_moment.v[i] = m;
        pc.second_moment.v[i] = v;
        const float step = (m / pc.bias_correction1) / (sqrt(v / pc.bias_correction2) + pc.epsilon);
        pc.params.v[i] -= learning_rate(i, n) * step;
    }
}
