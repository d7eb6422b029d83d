#pragma once
// The training passes. Like render/passes.hpp: each is one shader (shaders/<name>.comp) and one
// small host function that fills its push constants (the twin of the shader's Push block) and
// records the dispatch.
#include <cstdint>

#include "gpu/command_stream.hpp"

namespace vksplat::train {

using Address = VkDeviceAddress;

struct ActivatePush {
    Address raw, params;
    uint32_t count;
};
void record_activate(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline, const ActivatePush& push);

// blend_train.comp: render::BlendPush, then the transmittance and last-position images.
struct BlendTrainPush {
    Address camera, ranges, tile_values, footprints, colors, out_color_alpha, out_depth, out_contributors,
        out_transmittance, out_last;
};
void record_blend_train(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline, const BlendTrainPush& push,
                        uint32_t tiles_x, uint32_t tiles_y);

struct BlendBackwardPush {
    Address camera, ranges, tile_values, footprints, colors, transmittance, last, pixel_grad, splat_grads;
};
void record_blend_backward(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline,
                           const BlendBackwardPush& push, uint32_t tiles_x, uint32_t tiles_y);

struct PreprocessBackwardPush {
    Address camera, raw, tiles_touched, splat_grads, grads, counters, status, densify, means_depth;
};
void record_preprocess_backward(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline,
                                const PreprocessBackwardPush& push, uint32_t gaussian_count);

struct AdamPush {
    Address params, grads, first_moment, second_moment, status;
    uint32_t count, sh_floats;
    float lr_position, lr_scale, lr_rotation, lr_opacity, lr_sh_dc, lr_sh_rest;
    float beta1, beta2, epsilon, bias_correction1, bias_correction2;
};
void record_adam(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline, const AdamPush& push,
                 uint64_t floats);

}  // namespace vksplat::train
