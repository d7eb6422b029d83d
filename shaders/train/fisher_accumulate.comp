#version 460
// Adds one probe's G G^T to each Gaussian's Fisher sum, G = d L / d (mean, log-scales) from the
// backward pass of fisher_probe_signs' random picture gradient. One thread per Gaussian owns its
// 21 floats: no atomics, so the sums do not depend on the order the invocations run in.
#extension GL_GOOGLE_include_directive : require

#include "shaders/common/buffers.h"
#include "shaders/train/fisher_probes.h"

layout(local_size_x = 256) in;

layout(push_constant) uniform Push { FisherAccumulatePush pc; };

void main() {
    if (pc.status.v[0] != 0u) return;
    const uint n = pc.count;
    for (uint i = gl_GlobalInvocationID.x; i < n; i += gl_NumWorkGroups.x * gl_WorkGroupSize.x) {
        float g[6];
        for (uint k = 0u; k < 3u; ++k) {
            g[k] = pc.grads.v[positions_offset(n) + 3u * i + k];
            g[3u + k] = pc.grads.v[log_scales_offset(n) + 3u * i + k];
        }
        uint at = FISHER_FLOATS * i;
        for (uint r = 0u; r < 6u; ++r)
            for (uint c = r; c < 6u; ++c, ++at) pc.fisher.v[at] += g[r] * g[c];
    }
}
