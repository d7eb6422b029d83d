#include "render/passes.hpp"

namespace vksplat::render {

void record_indirect_args(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline,
                          const IndirectArgsPush& push) {
    stream.dispatch(pipeline, push, 1);
}

}  // namespace vksplat::render
