#include "render/passes.hpp"

namespace vksplat::render {

uint32_t groups_for(uint32_t count, uint32_t per_group) {
    const uint64_t groups = (static_cast<uint64_t>(count) + per_group - 1) / per_group;
    return static_cast<uint32_t>(groups < 65535 ? groups : 65535);
}

void record_preprocess(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline, const PreprocessPush& push,
                       uint32_t gaussian_count) {
    stream.dispatch(pipeline, push, groups_for(gaussian_count));
}

}  // namespace vksplat::render
