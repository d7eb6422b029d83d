#pragma once
// The training loss on the GPU: (1 - lambda) * L1 + lambda * (1 - SSIM), as the reference trainer
// computes it (L1 and SSIM means over every pixel and channel; SSIM with an 11x11 Gaussian window,
// sigma 1.5, zero padding, C1 = 0.01^2, C2 = 0.03^2), and its gradient with respect to the
// rendered image. A pixel whose photo alpha is 0 is masked out: it adds nothing to either term
// and gets no gradient from its own terms (the means still divide by every pixel, so a mask only
// removes terms). It still lies in the SSIM windows of its neighbours, so within 5 pixels of an
// unmasked pixel it gets their share of the gradient, as autograd of (mask * ssim_map) gives.
// One kernel computes the sums and the gradient, shaders/train/loss.comp; vksplat/reference/
// training_loss.hpp is the double-precision oracle.
#include <cstdint>
#include <memory>

#include "gpu/buffer.hpp"
#include "gpu/command_stream.hpp"
#include "gpu/kernel.hpp"

namespace vksplat::train {

// Device buffers of one width x height image pair, row-major, top row first.
struct LossInputs {
    VkDeviceAddress rendered = 0;  // vec4 per pixel: rgb (background included) and alpha, as the blend writes it
    VkDeviceAddress photo = 0;     // uint per pixel: RGBA8, r in the low byte; a = 0 masks the pixel out
    VkDeviceAddress gradient = 0;  // out: vec4 per pixel, dL/d rgb of `rendered` (w written as 0)
    uint32_t width = 0, height = 0;
    float ssim_weight = 0.2f;      // lambda
};

// Sums over the image, read back after the submission (LossPasses::last()).
struct LossValue {
    double loss = 0;       // (1 - lambda) * l1 + lambda * (1 - ssim)
    double l1 = 0;         // mean |rendered - photo| over pixels and channels (masked terms 0)
    double ssim = 0;       // mean SSIM over pixels and channels (masked terms 0)
    double mse = 0;        // mean squared error over pixels and channels, for PSNR (masked terms 0)
};

class LossPasses {
public:
    explicit LossPasses(const gpu::Context& context);
    ~LossPasses();
    LossPasses(const LossPasses&) = delete;
    LossPasses& operator=(const LossPasses&) = delete;

    // Host-visible buffers the sums are copied to, one per step that may be on the device at once
    // (the Trainer queues a step behind the one running).
    static constexpr int kReadbackSlots = 2;

    // Records the loss and its gradient; grows its scratch buffers for the image size
    // first (so call it outside any recording that other frames still use). Copies the sums to
    // readback `slot` (0 .. kReadbackSlots - 1). The caller records a barrier before it (the
    // rendered image and the photo must be visible to shaders) and after it (the gradient is
    // written by its dispatch). Throws std::invalid_argument for an empty image, or one of 2^32
    // pixels or more (the kernel indexes with 32 bits).
    void record(gpu::CommandStream& stream, const LossInputs& inputs, int slot = 0);
    // The sums of the last loss recorded into readback `slot`, once its submission has finished.
    LossValue last(int slot = 0) const;
    // Device bytes its scratch holds: the per-workgroup sums (no per-pixel maps).
    uint64_t device_bytes() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace vksplat::train
