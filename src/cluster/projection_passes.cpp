#include "cluster/projection_passes.hpp"

#include <algorithm>

namespace vksplat::cluster {
namespace {

// 256 per group in a grid-stride loop, at most 65535 groups.
uint32_t groups_for(uint32_t count) { return std::clamp((count + 255) / 256, 1u, 65535u); }

}  // namespace

void record_nearest_depth(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline,
                          const NearestDepthPush& push) {
    stream.dispatch(pipeline, push, groups_for(push.count));
}

void record_project(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline, const ProjectPush& push) {
    stream.dispatch(pipeline, push, groups_for(push.count));
}

}  // namespace vksplat::cluster
