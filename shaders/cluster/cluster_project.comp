#version 460
// Cluster projection, step 2: the region id under each Gaussian's projected centre, or -1 where the
// centre is outside the image, the Gaussian was culled, or it is occluded there. Two occlusion
// rules (push constant `rule`):
//   0, depth: occluded when it lies more than depth_ratio * z_min + depth_offset behind the nearest
//      centre z_min in its pixel (cluster_nearest_depth.comp);
//   1, blend: visible where its alpha * T at its centre pixel, measured by the blend pass, is at
//      least min_weight (w of `centres` holds that weight in this mode).
#extension GL_GOOGLE_include_directive : require

#include "shaders/cluster/projection.h"

layout(local_size_x = 256) in;

layout(push_constant) uniform Push { ClusterProjectPush pc; };

void main() {
    for (uint i = gl_GlobalInvocationID.x; i < pc.count; i += gl_NumWorkGroups.x * gl_WorkGroupSize.x) {
        const vec4 c = pc.centres.v[i];
        const ivec2 pixel = ivec2(floor(c.xy + 0.5));
        int label = -1;
        const bool inside = all(greaterThanEqual(pixel, ivec2(0))) && pixel.x < int(pc.width) && pixel.y < int(pc.height);
        if (inside && c.w > 0.0) {
            const uint at = uint(pixel.y) * pc.width + uint(pixel.x);
            bool seen;
            if (pc.rule == 0u) {
                const float z_min = uintBitsToFloat(pc.nearest.v[at]);
                seen = c.z - z_min <= pc.depth_ratio * z_min + pc.depth_offset;
            } else {
                seen = c.w >= pc.min_weight;
            }
            if (seen) label = pc.regions.v[at];
        }
        pc.labels.v[i] = label;
    }
}
