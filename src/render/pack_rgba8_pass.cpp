#include "render/passes.hpp"

namespace vksplat::render {

void record_pack_rgba8(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline, const PackRgba8Push& push) {
    stream.dispatch(pipeline, push, groups_for(push.pixels));
}

}  // namespace vksplat::render
