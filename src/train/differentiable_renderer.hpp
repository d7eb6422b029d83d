#pragma once
// DifferentiableRenderer: the renderer's frame on a TrainableScene, keeping what the backward pass
// needs, and that backward pass. Forward: TileBinning (with preprocess_trainable, which activates
// the raw parameters as it reads them) -> blend_train (the picture, and per pixel the final
// transmittance and where its list walk ended). Backward, from dL/d rgb
// per pixel: blend_backward (per-splat gradients of mean, conic, opacity, colour; per pixel or per
// splat, BlendBackward) -> preprocess_backward (gradients of the geometry) -> sh_backward (of the
// SH coefficients). All are recorded into the caller's command stream, so a training step is one
// submission. Kernels:
// shaders/train/{preprocess_trainable,blend_train,blend_backward,blend_backward_cas,
// blend_backward_fixed,blend_backward_per_splat,blend_backward_per_splat_cas,preprocess_backward,
// preprocess_backward_fixed,sh_backward}.comp, layouts in shaders/train/differentiable_renderer.h.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "gpu/buffer.hpp"
#include "gpu/command_stream.hpp"
#include "gpu/kernel.hpp"
#include "render/frame_layout.hpp"
#include "render/frame_resources.hpp"
#include "render/tile_binning.hpp"
#include "train/trainable_scene.hpp"
#include "vksplat/train/gradients.hpp"

namespace vksplat::shader::train {
struct BlendBackwardPush;
struct BlendTrainKernel;
struct BlendBackwardKernel;
struct BlendBackwardCasKernel;
struct BlendBackwardFixedKernel;
struct BlendBackwardPerSplatKernel;
struct BlendBackwardPerSplatCasKernel;
struct PreprocessBackwardPush;
struct ShBackwardKernel;
}  // namespace vksplat::shader::train

namespace vksplat::train {

// Which form of the blend backward runs next (BlendBackward): the one asked for, or, asked for
// `fastest`, the two in turn until each has kTrials timings, then the one whose median is lower
// (ties: per pixel), until the scene has doubled or halved since the timings began (training from
// SfM points grows it a hundredfold, and larger splats favour per splat): then both are timed
// again. Medians, because a step's time also moves with its view and with what else the GPU does.
class BlendBackwardChoice {
public:
    static constexpr size_t kTrials = 10;

    explicit BlendBackwardChoice(BlendBackward wanted) : wanted_(wanted), chosen_(wanted) {}
    // Before a step on a scene of `gaussians`.
    void scene_size(uint32_t gaussians);
    // per_pixel or per_splat.
    BlendBackward next() const;
    // The GPU time of a blend backward that ran in `form`; ignored once chosen.
    void timed(BlendBackward form, double milliseconds);
    // The queue gave no timings: settles on per pixel, the form that ran before there was a choice.
    void untimed();
    // per_pixel or per_splat once asked for or measured; `fastest` while measuring.
    BlendBackward chosen() const { return chosen_; }

private:
    BlendBackward wanted_, chosen_;
    uint32_t timed_gaussians_ = 0;  // the scene's size when the timings began
    std::vector<double> per_pixel_ms_, per_splat_ms_;
};

// The stage label of a blend backward in `form` ("blend backward (per pixel)", "... (per splat)"),
// so that the per-pass times of a run (train --profile, train_bench) say which form ran.
std::string blend_backward_stage(BlendBackward form);

class DifferentiableRenderer {
public:
    // How the blend backward sums gradients (GradientSums) and divides its work (BlendBackward).
    // Throws InputError for fixed_point on a device without 64-bit buffer atomics,
    // std::invalid_argument for fixed_point with per_splat.
    explicit DifferentiableRenderer(const gpu::Context& context, GradientSums sums = GradientSums::device_default,
                                    BlendBackward form = BlendBackward::fastest);
    ~DifferentiableRenderer();

    // Sizes the buffers for the scene and the image (keeps them where they suffice). Tile entries
    // start at a few per Gaussian and grow through grow_entries().
    void ensure(uint32_t gaussians, uint32_t pixels, uint32_t tiles);
    void grow_entries(uint32_t needed);
    // Frees the frame's buffers (sized by the scene, the tile entries or the image) until the next
    // ensure(), which allocates them again with the entry capacity learned so far: while the
    // trainer densifies, their memory holds the old scene's arrays instead.
    void release_frame();
    uint32_t entry_capacity() const { return frame_.entry_capacity; }

    // The forward frame of `scene` with `params` (its gaussian_count, sh_degree and entry
    // capacity filled in by the caller): leaves colour and alpha in color_alpha(). `beside_blend`
    // records commands just before the blend with no barrier between them, so that they run while
    // it does; the barrier after the blend waits for them.
    void record_forward(gpu::CommandStream& stream, const TrainableScene& scene, const render::CameraParams& params,
                        const std::function<void()>& beside_blend = {});
    // The gradients of every raw parameter from dL/d rgb per pixel (vec4, at `pixel_grad`): into
    // scene.grads, or, given a step's Adam settings (`adam`, shaders/train/adam_step.h), straight
    // into Adam's step of scene.params and its moments, so that they need no array of their own.
    // Zeroes the step status first; preprocess_backward sets its bits. With
    // `clear_overflow_mark` it clears the overflow mark too (shaders/train/parameter_layout.h):
    // for a step recorded again after an overflow, with no step queued before it. The blend
    // backward runs in blend_backward_choice().next()'s form.
    void record_backward(gpu::CommandStream& stream, const TrainableScene& scene, VkDeviceAddress pixel_grad,
                         bool clear_overflow_mark, VkDeviceAddress adam = 0);
    // After the submission of a record_backward and record_readback into `slot`: its blend
    // backward's time, for the choice of form (none from a frame that overflowed its tile entries).
    void learn_timings(const gpu::CommandStream& stream, int slot = 0);
    const BlendBackwardChoice& blend_backward_choice() const { return choice_; }
    // Host-visible readbacks, one per step that may be on the device at once (the Trainer queues
    // a step behind the one running).
    static constexpr int kReadbackSlots = 2;
    // Copies the frame counters and the step status to readback `slot` (after the submission:
    // entries_needed(slot), visible(slot), status(slot)).
    void record_readback(gpu::CommandStream& stream, int slot = 0);
    // Forward and backward of one view to fixed pixel gradients (vec4 per pixel at `pixel_grad`) in
    // one submission, re-run with grown tile entries until the frame fits; waits. For callers that
    // want the gradients of a loss of their own (train::render_gradients, the tests); with `adam`,
    // one Adam step by them, as record_backward takes it.
    void backpropagate(const TrainableScene& scene, const Camera& camera, const RenderSettings& settings,
                       VkDeviceAddress pixel_grad, VkDeviceAddress adam = 0);
    // The tile entries of the step read back into `slot`; throws GpuError when more than one frame
    // can sort (render::check_entries_sortable).
    uint32_t entries_needed(int slot = 0) const;
    uint32_t visible(int slot = 0) const;
    uint32_t status(int slot = 0) const;

    const gpu::Buffer& color_alpha() const { return frame_.color_alpha; }
    const gpu::Buffer& status_buffer() const { return status_; }
    // The blend backward's per-splat totals: floats, or with fixed_point sums 64-bit integers in
    // units of 2^-40 (shaders/train/differentiable_renderer.h).
    const gpu::Buffer& splat_grads() const { return splat_grads_; }
    // Device bytes its buffers hold.
    uint64_t device_bytes() const;

private:
    // Bytes of one per-splat total: a float, or an int64 with fixed_point sums.
    uint32_t splat_grad_bytes() const { return blend_backward_fixed_ ? 8 : 4; }
    // The float-sum blend backward in recorded_'s form.
    void record_blend_backward(gpu::CommandStream& stream, const shader::train::BlendBackwardPush& push);

    const gpu::Context& context_;
    render::TileBinning binning_;
    std::unique_ptr<gpu::Kernel<shader::train::BlendTrainKernel>> blend_;
    // With float atomics (per pixel and per splat), with compare-and-swap loops (both), or in
    // fixed point (per pixel, with the preprocess backward that reads its totals).
    std::unique_ptr<gpu::Kernel<shader::train::BlendBackwardKernel>> blend_backward_;
    std::unique_ptr<gpu::Kernel<shader::train::BlendBackwardPerSplatKernel>> per_splat_;
    std::unique_ptr<gpu::Kernel<shader::train::BlendBackwardCasKernel>> blend_backward_cas_;
    std::unique_ptr<gpu::Kernel<shader::train::BlendBackwardPerSplatCasKernel>> per_splat_cas_;
    std::unique_ptr<gpu::Kernel<shader::train::BlendBackwardFixedKernel>> blend_backward_fixed_;
    bool float_atomics_ = false;  // else compare-and-swap loops (or fixed point)
    BlendBackwardChoice choice_;
    BlendBackward recorded_ = BlendBackward::per_pixel;  // the form the last record_backward ran
    // Reads the blend backward's totals as floats, or as fixed-point integers.
    std::unique_ptr<gpu::PushKernel<shader::train::PreprocessBackwardPush>> preprocess_backward_;
    std::unique_ptr<gpu::Kernel<shader::train::ShBackwardKernel>> sh_backward_;
    render::FrameResources frame_;
    uint32_t capacity_ = 0;  // Gaussians the per-splat buffers below hold
    uint32_t released_entries_ = 0;  // the entry capacity before release_frame()
    uint32_t pixel_capacity_ = 0;
    gpu::Buffer splat_grads_;                      // per Gaussian
    gpu::Buffer sh_steps_;                         // per Gaussian: what the SH backward reads
    gpu::Buffer transmittance_, last_;             // per pixel
    gpu::Buffer status_;
    std::array<gpu::Buffer, kReadbackSlots> readbacks_;
    uint32_t tiles_x_ = 0, tiles_y_ = 0;
};

}  // namespace vksplat::train
