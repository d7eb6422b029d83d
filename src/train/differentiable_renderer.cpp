#include "train/differentiable_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "shaders/blend_backward.spv.h"
#include "shaders/blend_backward_cas.spv.h"
#include "shaders/blend_train.spv.h"
#include "shaders/preprocess_backward.spv.h"
#include "shaders/train_activate.spv.h"
#include "train/train_passes.hpp"
#include "vksplat/error.hpp"

namespace vksplat::train {
namespace {

constexpr uint32_t kInitialEntriesPerGaussian = 4;  // as the renderer starts
constexpr double kEntryGrowth = 1.25;

gpu::ComputePipeline blend_backward_pipeline(const gpu::Context& context, bool compare_and_swap) {
    if (context.info().float_atomics && !compare_and_swap)
        return {context, gpu::spirv_words(blend_backward_spv), sizeof(BlendBackwardPush), {}, "blend_backward"};
    return {context, gpu::spirv_words(blend_backward_cas_spv), sizeof(BlendBackwardPush), {}, "blend_backward_cas"};
}

}  // namespace

DifferentiableRenderer::DifferentiableRenderer(const gpu::Context& c, bool compare_and_swap)
    : context_(c),
      binning_(c),
      activate_(c, gpu::spirv_words(train_activate_spv), sizeof(ActivatePush), {}, "train_activate"),
      blend_(c, gpu::spirv_words(blend_train_spv), sizeof(BlendTrainPush), {}, "blend_train"),
      blend_backward_(blend_backward_pipeline(c, compare_and_swap)),
      preprocess_backward_(c, gpu::spirv_words(preprocess_backward_spv), sizeof(PreprocessBackwardPush), {},
                           "preprocess_backward"),
      frame_(c),
      status_(c, sizeof(uint32_t), gpu::MemoryKind::device, "training step status"),
      readback_(c, (render::kCounterCount + 1) * sizeof(uint32_t), gpu::MemoryKind::readback,
                "training step readback") {
    std::memset(readback_.mapped(), 0, readback_.size());
}

void DifferentiableRenderer::ensure(uint32_t gaussians, uint32_t pixels, uint32_t tiles) {
    frame_.ensure_gaussians(gaussians);
    frame_.ensure_image(pixels, tiles);
    if (frame_.entry_capacity == 0) frame_.ensure_entries(std::max(gaussians, 1u) * kInitialEntriesPerGaussian);
    if (gaussians > capacity_) {
        render_params_ = gpu::Buffer();
        render_params_ = gpu::Buffer(context_, uint64_t(gaussians) * 48, gpu::MemoryKind::device, "activated parameters");
        splat_grads_ = gpu::Buffer();
        splat_grads_ = gpu::Buffer(context_, uint64_t(gaussians) * kSplatGradStride * 4, gpu::MemoryKind::device,
                                   "per-splat gradients");
        capacity_ = gaussians;
    }
    if (pixels > pixel_capacity_) {
        transmittance_ = gpu::Buffer();
        transmittance_ = gpu::Buffer(context_, uint64_t(pixels) * 4, gpu::MemoryKind::device, "final transmittance");
        last_ = gpu::Buffer();
        last_ = gpu::Buffer(context_, uint64_t(pixels) * 4, gpu::MemoryKind::device, "last blended positions");
        pixel_capacity_ = pixels;
    }
}

void DifferentiableRenderer::grow_entries(uint32_t needed) {
    frame_.ensure_entries(static_cast<uint32_t>(std::ceil(needed * kEntryGrowth)));
}

void DifferentiableRenderer::record_forward(gpu::CommandStream& stream, const TrainableScene& scene,
                                            const render::CameraParams& camera_params) {
    // Densification reads the radii the projection holds.
    render::CameraParams params = camera_params;
    params.write_projection = 1;
    const uint32_t n = scene.layout.count;
    tiles_x_ = params.size[2];
    tiles_y_ = params.size[3];
    record_activate(stream, activate_, {scene.params.address(), render_params_.address(), n});
    // TileBinning's first barrier orders the activation before its preprocess.
    binning_.record(stream, frame_, params, {render_params_.address(), scene.sh_address(), n});
    auto& f = frame_;
    record_blend_train(stream, blend_,
                       {f.camera.address(), f.ranges.address(), f.tile_values.address(), f.footprints.address(),
                        f.colors.address(), f.color_alpha.address(), f.depth.address(), f.contributors.address(),
                        transmittance_.address(), last_.address()},
                       tiles_x_, tiles_y_);
    stream.barrier();
    stream.mark("blend");
}

void DifferentiableRenderer::record_backward(gpu::CommandStream& stream, const TrainableScene& scene,
                                             VkDeviceAddress pixel_grad) {
    auto& f = frame_;
    stream.fill(splat_grads_, 0, 0, uint64_t(scene.layout.count) * kSplatGradStride * 4);
    stream.fill(status_, 0);
    stream.barrier();
    record_blend_backward(stream, blend_backward_,
                          {f.camera.address(), f.ranges.address(), f.tile_values.address(), f.footprints.address(),
                           f.colors.address(), transmittance_.address(), last_.address(), pixel_grad,
                           splat_grads_.address()},
                          tiles_x_, tiles_y_);
    stream.barrier();
    stream.mark("blend backward");
    record_preprocess_backward(stream, preprocess_backward_,
                               {f.camera.address(), scene.params.address(), f.tiles_touched.address(),
                                splat_grads_.address(), scene.grads.address(), f.counters.address(), status_.address(),
                                scene.densify.address(), f.means_depth.address()},
                               scene.layout.count);
    stream.barrier();
    stream.mark("preprocess backward");
}

void DifferentiableRenderer::record_readback(gpu::CommandStream& stream) {
    stream.copy(frame_.counters, readback_, render::kCounterCount * sizeof(uint32_t));
    stream.copy(status_, readback_, sizeof(uint32_t), 0, render::kCounterCount * sizeof(uint32_t));
}

uint32_t DifferentiableRenderer::entries_needed() const {
    const uint32_t needed = static_cast<const uint32_t*>(readback_.mapped())[render::kCounterEntriesNeeded];
    render::check_entries_sortable(needed);
    return needed;
}

uint32_t DifferentiableRenderer::visible() const {
    return static_cast<const uint32_t*>(readback_.mapped())[render::kCounterVisible];
}

uint32_t DifferentiableRenderer::status() const {
    return static_cast<const uint32_t*>(readback_.mapped())[render::kCounterCount];
}

uint64_t DifferentiableRenderer::device_bytes() const {
    return frame_.device_bytes() + render_params_.size() + splat_grads_.size() + transmittance_.size() +
           last_.size() + status_.size();
}

void DifferentiableRenderer::backpropagate(const TrainableScene& scene, const Camera& camera,
                                           const RenderSettings& settings, VkDeviceAddress pixel_grad) {
    gpu::CommandStream stream(context_);
    for (;;) {
        const auto params =
            render::make_camera_params(camera, settings, scene.layout.count, scene.sh_degree, false, entry_capacity());
        stream.begin();
        record_forward(stream, scene, params);
        record_backward(stream, scene, pixel_grad);
        record_readback(stream);
        stream.barrier_before_host_read();
        stream.submit_and_wait();
        const uint32_t needed = entries_needed();  // checked even when the frame fits
        if ((status() & kStepOverflowed) == 0) return;
        grow_entries(needed);
    }
}

}  // namespace vksplat::train
