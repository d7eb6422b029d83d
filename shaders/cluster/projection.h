// The cluster projection's kernels (cluster_nearest_depth.comp, cluster_project.comp), recorded
// by src/cluster/projection.cpp (Projector::project): one thread per Gaussian, 256 per workgroup.
#ifndef VKSPLAT_CLUSTER_PROJECTION_H
#define VKSPLAT_CLUSTER_PROJECTION_H

#include "shaders/common/buffers.h"

SHADER_NAMESPACE_BEGIN(cluster)

BUFFER_REFERENCE(Ints, int, 4)

// cluster_nearest_depth.comp: per pixel, the depth of the nearest visible centre.
struct ClusterNearestDepthPush {
    Vec4s centres;   // per Gaussian: screen x, y (pixel centres at integers), view depth, visible (> 0)
    Uints nearest;   // out: per pixel, float bits of the nearest centre's depth
    uint count;
    uint width;
    uint height;
};

// cluster_project.comp: per Gaussian, the region its centre falls in (or -1).
struct ClusterProjectPush {
    Vec4s centres;   // per Gaussian: screen x, y, view depth, visible flag (depth) or centre weight (blend)
    Uints nearest;   // per pixel: nearest centre depth as float bits (depth rule only)
    Ints regions;    // per pixel: region id, -1 for none
    Ints labels;     // out: per Gaussian
    uint count;
    uint width;
    uint height;
    uint rule;       // 0: depth, 1: blend
    float depth_ratio;
    float depth_offset;
    float min_weight;
};

SHADER_NAMESPACE_END

#endif
