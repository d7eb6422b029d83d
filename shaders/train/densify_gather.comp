#version 460
// Densification's data movement, one array at a time (parameters, then each of Adam's moments,
// so that the old and the new scene are never on the device whole at once): the new array's
// Gaussian j is a copy of the old array's Gaussian sources[j] (every block of parameter_layout.h),
// with two exceptions the host's plan (src/train/densify.hpp) sets: from zero_from on it holds
// zeros (new Gaussians' moments start at zero, as the reference's optimizer state does), and from
// override_from on the position, log-scale and opacity the host chose (split samples, MCMC
// relocations). The host decides which Gaussians to clone, split and prune from a small download
// (positions, scales, rotations, opacities and the densification sums); the bulk of the state
// never leaves the device.
#extension GL_GOOGLE_include_directive : require

#include "shaders/common/buffers.h"
#include "shaders/train/densify.h"

layout(local_size_x = 256) in;

layout(push_constant) uniform Push { DensifyGatherPush pc; };

// Copies `floats` floats of one Gaussian from old offset `from` to new offset `to`.
void move(uint from, uint to, uint floats, bool zero) {
    for (uint k = 0u; k < floats; ++k) pc.new_values.v[to + k] = zero ? 0.0 : pc.old_values.v[from + k];
}

void main() {
    const uint n = pc.old_count, m = pc.new_count;
    for (uint j = gl_GlobalInvocationID.x; j < m; j += gl_NumWorkGroups.x * gl_WorkGroupSize.x) {
        const uint i = pc.sources.v[j];
        const bool zero = j >= pc.zero_from;
        move(positions_offset(n) + 3u * i, positions_offset(m) + 3u * j, 3u, zero);
        move(log_scales_offset(n) + 3u * i, log_scales_offset(m) + 3u * j, 3u, zero);
        move(rotations_offset(n) + 4u * i, rotations_offset(m) + 4u * j, 4u, zero);
        move(opacities_offset(n) + i, opacities_offset(m) + j, 1u, zero);
        move(sh_offset(n) + pc.sh_floats * i, sh_offset(m) + pc.sh_floats * j, pc.sh_floats, zero);
        if (j >= pc.override_from) {
            const uint s = 7u * (j - pc.override_from);
            for (uint k = 0u; k < 3u; ++k) {
                pc.new_values.v[positions_offset(m) + 3u * j + k] = pc.overrides.v[s + k];
                pc.new_values.v[log_scales_offset(m) + 3u * j + k] = pc.overrides.v[s + 3u + k];
            }
            pc.new_values.v[opacities_offset(m) + j] = pc.overrides.v[s + 6u];
        }
    }
}
