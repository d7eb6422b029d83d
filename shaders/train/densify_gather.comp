#version 460
// Densification's data movement: the new scene's Gaussian j is a copy of the old scene's
// Gaussian sources[j] (parameters and Adam's moments, every block of parameter_layout.h), with two
// exceptions the host's plan (src/train/densify.hpp) sets: Gaussians from fresh_from on are new,
// so their moments start at zero, as the reference's optimizer state does; and Gaussians from
// override_from on take the position, log-scale and opacity the host chose for them (split
// samples, MCMC relocations). The host
// decides which Gaussians to clone, split and prune from a small download (positions, scales,
// rotations, opacities and the densification sums); the bulk of the state never leaves the device.
#extension GL_GOOGLE_include_directive : require

#include "shaders/common/buffers.h"
#include "shaders/train/densify.h"

layout(local_size_x = 256) in;

layout(push_constant) uniform Push { DensifyGatherPush pc; };

// Copies `floats` floats of one Gaussian from old offset `from` to new offset `to`.
void move(uint from, uint to, uint floats, bool fresh) {
    for (uint k = 0u; k < floats; ++k) {
        pc.new_params.v[to + k] = pc.old_params.v[from + k];
        pc.new_first.v[to + k] = fresh ? 0.0 : pc.old_first.v[from + k];
        pc.new_second.v[to + k] = fresh ? 0.0 : pc.old_second.v[from + k];
    }
}

void main() {
    const uint n = pc.old_count, m = pc.new_count;
    for (uint j = gl_GlobalInvocationID.x; j < m; j += gl_NumWorkGroups.x * gl_WorkGroupSize.x) {
        const uint i = pc.sources.v[j];
        const bool fresh = j >= pc.fresh_from;
        move(positions_offset(n) + 3u * i, positions_offset(m) + 3u * j, 3u, fresh);
        move(log_scales_offset(n) + 3u * i, log_scales_offset(m) + 3u * j, 3u, fresh);
        move(rotations_offset(n) + 4u * i, rotations_offset(m) + 4u * j, 4u, fresh);
        move(opacities_offset(n) + i, opacities_offset(m) + j, 1u, fresh);
        move(sh_offset(n) + pc.sh_floats * i, sh_offset(m) + pc.sh_floats * j, pc.sh_floats, fresh);
        if (j >= pc.override_from) {
            const uint s = 7u * (j - pc.override_from);
            for (uint k = 0u; k < 3u; ++k) {
                pc.new_params.v[positions_offset(m) + 3u * j + k] = pc.overrides.v[s + k];
                pc.new_params.v[log_scales_offset(m) + 3u * j + k] = pc.overrides.v[s + 3u + k];
            }
            pc.new_params.v[opacities_offset(m) + j] = pc.overrides.v[s + 6u];
        }
    }
}
