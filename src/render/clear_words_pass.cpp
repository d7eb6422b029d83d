#include "render/passes.hpp"

namespace vksplat::render {

void record_clear_words(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline, const ClearWordsPush& push) {
    stream.dispatch(pipeline, push, groups_for(push.count));
}

}  // namespace vksplat::render
