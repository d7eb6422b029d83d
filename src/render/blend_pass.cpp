#include "render/passes.hpp"

namespace vksplat::render {

void record_blend(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline, const BlendPush& push,
                  uint32_t tiles_x, uint32_t tiles_y) {
    stream.dispatch(pipeline, push, tiles_x, tiles_y);
}

void record_blend_carry(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline, const BlendCarryPush& push,
                        uint32_t tiles_x, uint32_t tiles_y) {
    stream.dispatch(pipeline, push, tiles_x, tiles_y);
}

void record_blend_stats_carry(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline,
                              const BlendStatsCarryPush& push, uint32_t tiles_x, uint32_t tiles_y) {
    stream.dispatch(pipeline, push, tiles_x, tiles_y);
}

void record_blend_stats(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline,
                        const BlendStatsPush& push, uint32_t tiles_x, uint32_t tiles_y) {
    stream.dispatch(pipeline, push, tiles_x, tiles_y);
}

}  // namespace vksplat::render
