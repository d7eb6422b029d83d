#pragma once
// The two passes of the cluster projection: one shader each (shaders/cluster_*.comp) and the host
// function that fills its push constants and records the dispatch.
#include <cstdint>

#include "gpu/command_stream.hpp"

namespace vksplat::cluster {

using Address = VkDeviceAddress;

struct NearestDepthPush {
    Address centres, nearest;
    uint32_t count, width, height;
};
void record_nearest_depth(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline,
                          const NearestDepthPush& push);

struct ProjectPush {
    Address centres, nearest, regions, labels;
    uint32_t count, width, height, rule;
    float depth_ratio, depth_offset, min_weight;
};
void record_project(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline, const ProjectPush& push);

}  // namespace vksplat::cluster
