#include "train/differentiable_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "render/entry_growth.hpp"
#include "shaders/train/blend_backward.kernel.hpp"
#include "shaders/train/blend_backward_cas.kernel.hpp"
#include "shaders/train/blend_backward_fixed.kernel.hpp"
#include "shaders/train/blend_backward_per_splat.kernel.hpp"
#include "shaders/train/blend_backward_per_splat_cas.kernel.hpp"
#include "shaders/train/blend_train.kernel.hpp"
#include "shaders/train/preprocess_backward.kernel.hpp"
#include "shaders/train/preprocess_backward_fixed.kernel.hpp"
#include "shaders/train/preprocess_trainable.kernel.hpp"
#include "shaders/train/sh_backward.kernel.hpp"
#include "stats/median.hpp"
#include "vksplat/error.hpp"

namespace vksplat::train {

using namespace shader::train;

void BlendBackwardChoice::scene_size(uint32_t gaussians) {
    if (wanted_ != BlendBackward::fastest) return;
    if (per_pixel_ms_.empty() && per_splat_ms_.empty()) timed_gaussians_ = gaussians;
    if (uint64_t(gaussians) <= 2 * uint64_t(timed_gaussians_) && 2 * uint64_t(gaussians) >= timed_gaussians_) return;
    chosen_ = BlendBackward::fastest;
    per_pixel_ms_.clear();
    per_splat_ms_.clear();
    timed_gaussians_ = gaussians;
}

BlendBackward BlendBackwardChoice::next() const {
    if (chosen_ != BlendBackward::fastest) return chosen_;
    return per_pixel_ms_.size() <= per_splat_ms_.size() ? BlendBackward::per_pixel : BlendBackward::per_splat;
}

void BlendBackwardChoice::timed(BlendBackward form, double milliseconds) {
    if (chosen_ != BlendBackward::fastest) return;
    (form == BlendBackward::per_splat ? per_splat_ms_ : per_pixel_ms_).push_back(milliseconds);
    if (per_pixel_ms_.size() < kTrials || per_splat_ms_.size() < kTrials) return;
    chosen_ = stats::median(per_splat_ms_) < stats::median(per_pixel_ms_) ? BlendBackward::per_splat
                                                                          : BlendBackward::per_pixel;
}

void BlendBackwardChoice::untimed() {
    if (chosen_ == BlendBackward::fastest) chosen_ = BlendBackward::per_pixel;
}

std::string blend_backward_stage(BlendBackward form) {
    return form == BlendBackward::per_splat ? "blend backward (per splat)" : "blend backward (per pixel)";
}

namespace {

// Fixed-point sums have no per-splat kernel: their runs keep one form.
BlendBackward form_for(GradientSums sums, BlendBackward form) {
    if (sums != GradientSums::fixed_point) return form;
    if (form == BlendBackward::per_splat)
        throw std::invalid_argument("the per-splat blend backward has no fixed-point sums");
    return BlendBackward::per_pixel;
}

}  // namespace

DifferentiableRenderer::DifferentiableRenderer(const gpu::Context& c, GradientSums sums, BlendBackward form)
    : context_(c),
      binning_(c, std::make_unique<gpu::Kernel<PreprocessTrainableKernel>>(c)),
      blend_(std::make_unique<gpu::Kernel<BlendTrainKernel>>(c)),
      choice_(form_for(sums, form)),
      sh_backward_(std::make_unique<gpu::Kernel<ShBackwardKernel>>(c)),
      frame_(c),
      status_(c, kStatusWords * sizeof(uint32_t), gpu::MemoryKind::device, "training step status") {
    for (gpu::Buffer& readback : readbacks_) {
        readback = gpu::Buffer(c, (render::kCounterCount + 1) * sizeof(uint32_t), gpu::MemoryKind::readback,
                               "training step readback");
        std::memset(readback.mapped(), 0, readback.size());
    }
    // The overflow mark starts clear; only steps recorded again after an overflow clear it.
    gpu::CommandStream clear(c, 0);
    clear.begin();
    clear.fill(status_, 0);
    clear.submit_and_wait();
    if (sums == GradientSums::fixed_point) {
        if (!c.info().int64_atomics)
            throw InputError("--deterministic", c.info().name + " has no 64-bit buffer atomics, which its "
                                                "order-independent gradient sums need");
        blend_backward_fixed_ = std::make_unique<gpu::Kernel<BlendBackwardFixedKernel>>(c);
        preprocess_backward_ = std::make_unique<gpu::Kernel<PreprocessBackwardFixedKernel>>(c);
    } else {
        preprocess_backward_ = std::make_unique<gpu::Kernel<PreprocessBackwardKernel>>(c);
    }
    float_atomics_ = c.info().float_atomics && sums == GradientSums::device_default;
}

void DifferentiableRenderer::record_blend_backward(gpu::CommandStream& stream, const BlendBackwardPush& push) {
    // The kernels of a form are built when it first runs: a frame that is never timed (render_gradients)
    // builds one.
    const auto& c = context_;
    if (recorded_ == BlendBackward::per_splat && float_atomics_) {
        if (!per_splat_) per_splat_ = std::make_unique<gpu::Kernel<BlendBackwardPerSplatKernel>>(c);
        stream.dispatch(*per_splat_, push, tiles_x_, tiles_y_);
    } else if (recorded_ == BlendBackward::per_splat) {
        if (!per_splat_cas_) per_splat_cas_ = std::make_unique<gpu::Kernel<BlendBackwardPerSplatCasKernel>>(c);
        stream.dispatch(*per_splat_cas_, push, tiles_x_, tiles_y_);
    } else if (float_atomics_) {
        if (!blend_backward_) blend_backward_ = std::make_unique<gpu::Kernel<BlendBackwardKernel>>(c);
        stream.dispatch(*blend_backward_, push, tiles_x_, tiles_y_);
    } else {
        if (!blend_backward_cas_) blend_backward_cas_ = std::make_unique<gpu::Kernel<BlendBackwardCasKernel>>(c);
        stream.dispatch(*blend_backward_cas_, push, tiles_x_, tiles_y_);
    }
}

DifferentiableRenderer::~DifferentiableRenderer() = default;

void DifferentiableRenderer::ensure(uint32_t gaussians, uint32_t pixels, uint32_t tiles) {
    frame_.ensure_gaussians(gaussians);
    frame_.ensure_image(pixels, tiles);
    // The first frame starts from a few entries per Gaussian; after release_frame() the
    // capacity learned before comes back as it was (sized anew by the scene it could exceed it).
    if (frame_.entry_capacity == 0)
        frame_.ensure_entries(released_entries_ ? released_entries_
                                                : std::max(gaussians, 1u) * render::kInitialEntriesPerGaussian);
    if (gaussians > capacity_) {
        gpu::replace(splat_grads_, context_, uint64_t(gaussians) * kSplatGradStride * splat_grad_bytes(),
                     gpu::MemoryKind::device, "per-splat gradients");
        gpu::replace(sh_steps_, context_, uint64_t(gaussians) * 32, gpu::MemoryKind::device, "SH backward's inputs");
        capacity_ = gaussians;
    }
    if (pixels > pixel_capacity_) {
        gpu::replace(transmittance_, context_, uint64_t(pixels) * 4, gpu::MemoryKind::device, "final transmittance");
        gpu::replace(last_, context_, uint64_t(pixels) * 4, gpu::MemoryKind::device, "last blended positions");
        pixel_capacity_ = pixels;
    }
}

void DifferentiableRenderer::release_frame() {
    if (frame_.entry_capacity) released_entries_ = frame_.entry_capacity;
    frame_.release();
    splat_grads_ = gpu::Buffer();
    sh_steps_ = gpu::Buffer();
    transmittance_ = gpu::Buffer();
    last_ = gpu::Buffer();
    capacity_ = pixel_capacity_ = 0;
}

void DifferentiableRenderer::grow_entries(uint32_t needed) {
    frame_.ensure_entries(render::grown_entry_capacity(needed));
}

void DifferentiableRenderer::record_forward(gpu::CommandStream& stream, const TrainableScene& scene,
                                            const render::CameraParams& camera_params,
                                            const std::function<void()>& beside_blend) {
    // Densification reads the radii the projection holds.
    render::CameraParams params = camera_params;
    params.write_projection = 1;
    const uint32_t n = scene.layout.count;
    tiles_x_ = params.size[2];
    tiles_y_ = params.size[3];
    // preprocess_trainable.comp reads the raw parameters and activates them as it reads them.
    binning_.record(stream, frame_, params, {scene.params.address(), scene.sh_address(), n});
    auto& f = frame_;
    if (beside_blend) beside_blend();
    stream.dispatch(*blend_,
                    {.blend = render::blend_frame(f),
                     .train = {.out_transmittance = transmittance_.address(), .out_last = last_.address()}},
                    tiles_x_, tiles_y_);
    stream.barrier();
    stream.mark("blend");
}

void DifferentiableRenderer::record_backward(gpu::CommandStream& stream, const TrainableScene& scene,
                                             VkDeviceAddress pixel_grad, bool clear_overflow_mark,
                                             VkDeviceAddress adam) {
    if (!adam && !scene.grads)
        throw std::logic_error("DifferentiableRenderer::record_backward: no Adam settings and no gradient array");
    auto& f = frame_;
    choice_.scene_size(scene.layout.count);
    recorded_ = choice_.next();
    const uint32_t grad_floats = scene.layout.count * kSplatGradStride;
    stream.fill(splat_grads_, 0, 0, uint64_t(grad_floats) * splat_grad_bytes());
    stream.fill(status_, 0, 0, clear_overflow_mark ? VK_WHOLE_SIZE : sizeof(uint32_t));
    stream.barrier();
    const BlendBackwardPush backward{.camera = f.camera.address(),
                                     .ranges = f.ranges.address(),
                                     .tile_values = f.tile_values.address(),
                                     .footprints = f.footprints.address(),
                                     .colors = f.colors.address(),
                                     .transmittance = transmittance_.address(),
                                     .last = last_.address(),
                                     .pixel_grad = pixel_grad,
                                     .splat_grads = splat_grads_.address(),
                                     .status = status_.address()};
    if (blend_backward_fixed_) stream.dispatch(*blend_backward_fixed_, backward, tiles_x_, tiles_y_);
    else record_blend_backward(stream, backward);
    stream.barrier();
    stream.mark(blend_backward_stage(recorded_));
    const VkDeviceAddress sh_steps = sh_steps_.address();
    const PreprocessBackwardPush preprocess{.camera = f.camera.address(),
                                            .raw = scene.params.address(),
                                            .tiles_touched = f.tiles_touched.address(),
                                            .splat_grads = splat_grads_.address(),
                                            .grads = scene.grads.address(),
                                            .counters = f.counters.address(),
                                            .status = status_.address(),
                                            .densify = scene.densify.address(),
                                            .means_depth = f.means_depth.address(),
                                            .sh_steps = sh_steps,
                                            .adam = adam};
    stream.dispatch(*preprocess_backward_, preprocess, gpu::groups_for(scene.layout.count));
    stream.barrier();
    stream.mark(adam ? "preprocess backward + Adam" : "preprocess backward");
    const uint64_t sh_floats = uint64_t(scene.layout.count) * scene.layout.sh_coefficients * 3;
    stream.dispatch(*sh_backward_,
                    {.camera = f.camera.address(),
                     .raw = scene.params.address(),
                     .grads = scene.grads.address(),
                     .counters = f.counters.address(),
                     .status = status_.address(),
                     .sh_steps = sh_steps,
                     .adam = adam},
                    gpu::groups_for(uint32_t((sh_floats + 3) / 4 + 1)));  // chunks of 4, the block unaligned
    stream.barrier();
    stream.mark(adam ? "SH backward + Adam" : "SH backward");
}

void DifferentiableRenderer::learn_timings(const gpu::CommandStream& stream, int slot) {
    // A frame that ran out of tile entries walked cut lists: its time says nothing.
    if (status(slot) & kStepOverflowed) return;
    // The stage's label says which form ran: the Trainer records the next step, perhaps in the
    // other form, before it learns from this one.
    for (const auto& stage : stream.stage_times())
        for (const BlendBackward form : {BlendBackward::per_pixel, BlendBackward::per_splat})
            if (stage.label == blend_backward_stage(form)) {
                choice_.timed(form, stage.milliseconds);
                return;
            }
    choice_.untimed();
}

void DifferentiableRenderer::record_readback(gpu::CommandStream& stream, int slot) {
    const gpu::Buffer& readback = readbacks_.at(size_t(slot));
    stream.copy(frame_.counters, readback, render::kCounterCount * sizeof(uint32_t));
    stream.copy(status_, readback, sizeof(uint32_t), 0, render::kCounterCount * sizeof(uint32_t));
}

uint32_t DifferentiableRenderer::entries_needed(int slot) const {
    const uint32_t needed =
        static_cast<const uint32_t*>(readbacks_.at(size_t(slot)).mapped())[render::kCounterEntriesNeeded];
    render::check_entries_sortable(needed);
    return needed;
}

uint32_t DifferentiableRenderer::visible(int slot) const {
    return static_cast<const uint32_t*>(readbacks_.at(size_t(slot)).mapped())[render::kCounterVisible];
}

uint32_t DifferentiableRenderer::status(int slot) const {
    return static_cast<const uint32_t*>(readbacks_.at(size_t(slot)).mapped())[render::kCounterCount];
}

uint64_t DifferentiableRenderer::device_bytes() const {
    return frame_.device_bytes() + splat_grads_.size() + sh_steps_.size() + transmittance_.size() + last_.size() +
           status_.size();
}

void DifferentiableRenderer::backpropagate(const TrainableScene& scene, const Camera& camera,
                                           const RenderSettings& settings, VkDeviceAddress pixel_grad,
                                           VkDeviceAddress adam) {
    gpu::CommandStream stream(context_);
    for (uint32_t attempts = 1;; ++attempts) {
        const auto params =
            render::make_camera_params(camera, settings, scene.layout.count, scene.sh_degree, false, entry_capacity());
        stream.begin();
        record_forward(stream, scene, params);
        // Nothing is queued, so no overflow is pending; a frame that overflows steps nothing by Adam.
        record_backward(stream, scene, pixel_grad, true, adam);
        record_readback(stream);
        stream.barrier_before_host_read();
        stream.submit_and_wait();
        learn_timings(stream);
        const uint32_t needed = entries_needed();  // checked even when the frame fits
        if ((status() & kStepOverflowed) == 0) return;
        render::check_frame_attempts(attempts, "view '" + camera.name + "'");
        grow_entries(needed);
    }
}

}  // namespace vksplat::train
