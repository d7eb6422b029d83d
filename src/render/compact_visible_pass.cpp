#include "render/passes.hpp"

namespace vksplat::render {

void record_compact_visible(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline,
                            const CompactVisiblePush& push, uint32_t gaussian_count) {
    stream.dispatch(pipeline, push, groups_for(gaussian_count));
}

}  // namespace vksplat::render
