#version 460
// Turns a count the GPU just produced into dispatch arguments, so the passes that follow are
// sized without a CPU round trip. The count is clamped to a capacity (the buffers' size); the
// unclamped count stays where it was, for the host to grow the buffers after the frame.
#extension GL_GOOGLE_include_directive : require

#include "shaders/render/tile_binning.h"

layout(local_size_x = 1) in;

layout(push_constant) uniform Push { IndirectArgsPush pc; };

void main() {
    const uint count = min(pc.count_in.v[0], pc.capacity);
    pc.count_out.v[0] = count;
    pc.args.v[0] = DispatchArgs(groups_for(count, pc.per_group), 1u, 1u);
}
