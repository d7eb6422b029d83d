#include "render/passes.hpp"

namespace vksplat::render {

void record_emit_tile_entries(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline,
                              const EmitTileEntriesPush& push, const gpu::Buffer& args, VkDeviceSize args_offset) {
    stream.dispatch_indirect(pipeline, push, args, args_offset);
}

}  // namespace vksplat::render
