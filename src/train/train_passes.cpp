#include "train/train_passes.hpp"

#include "gpu/kernel.hpp"

namespace vksplat::train {

void record_activate(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline, const ActivatePush& push) {
    stream.dispatch(pipeline, push, gpu::groups_for(push.count));
}

void record_blend_train(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline, const BlendTrainPush& push,
                        uint32_t tiles_x, uint32_t tiles_y) {
    stream.dispatch(pipeline, push, tiles_x, tiles_y);
}

void record_blend_backward(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline,
                           const BlendBackwardPush& push, uint32_t tiles_x, uint32_t tiles_y) {
    stream.dispatch(pipeline, push, tiles_x, tiles_y);
}

void record_preprocess_backward(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline,
                                const PreprocessBackwardPush& push, uint32_t gaussian_count) {
    stream.dispatch(pipeline, push, gpu::groups_for(gaussian_count));
}

void record_adam(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline, const AdamPush& push,
                 uint64_t floats) {
    stream.dispatch(pipeline, push, gpu::groups_for(static_cast<uint32_t>(std::min<uint64_t>(floats, 0xffffffffu))));
}

}  // namespace vksplat::train
