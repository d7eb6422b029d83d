#version 460
// The reference trainer's opacity reset: every opacity to at most max_opacity (here as its logit),
// and the opacity's Adam moments to zero (replace_tensor_to_optimizer), on the device.
#extension GL_GOOGLE_include_directive : require

#include "shaders/common/buffers.h"
#include "shaders/train/densify.h"

layout(local_size_x = 256) in;

layout(push_constant) uniform Push { ResetOpacityPush pc; };

void main() {
    const uint n = pc.count;
    for (uint i = gl_GlobalInvocationID.x; i < n; i += gl_NumWorkGroups.x * gl_WorkGroupSize.x) {
        const uint at = opacities_offset(n) + i;
        pc.params.v[at] = min(pc.params.v[at], pc.max_logit);
        pc.first_moment.v[at] = 0.0;
        pc.second_moment.v[at] = 0.0;
    }
}
