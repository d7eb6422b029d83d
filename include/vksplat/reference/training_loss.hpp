#pragma once
// The training loss of the reference 3DGS trainer (graphdeco-inria gaussian-splatting,
// train.py with utils/loss_utils.py), in double precision: THE ORACLE for the GPU loss
// (src/train/loss_passes.hpp). Kept simple rather than fast: direct 11 x 11 window sums.
//
//   loss = (1 - lambda) * L1 + lambda * (1 - SSIM)
//   L1   = mean over pixels and channels of mask * |x - y|
//   SSIM = mean over pixels and channels of mask * s, s the SSIM map of each channel with the
//          11 x 11 Gaussian window of sigma 1.5, zero padding outside the image (F.conv2d with
//          padding 5), C1 = 0.01^2, C2 = 0.03^2
//   MSE  = mean over pixels and channels of mask * (x - y)^2 (not in the loss; for PSNR)
// x is the rendered image, y the photo. The means divide by every pixel: a mask only removes
// terms. A masked pixel still enters the windows of its neighbours, so its gradient is not
// always 0: it holds what the SSIM of unmasked neighbours gets from it.
#include <cstdint>
#include <span>
#include <vector>

namespace vksplat::reference {

struct TrainingLoss {
    double loss = 0;
    double l1 = 0;
    double ssim = 0;
    double mse = 0;
    std::vector<double> gradient;  // dL/d rendered: rgb per pixel, row-major, top row first
};

// rendered_rgb and photo_rgb: 3 values per pixel, row-major, top row first. mask: one per pixel,
// 0 = masked out, or empty when every pixel counts. Throws std::invalid_argument when a size
// does not match width * height or the image is empty. The L1 term's derivative at x = y is 0.
TrainingLoss training_loss(int width, int height, std::span<const double> rendered_rgb,
                           std::span<const float> photo_rgb, std::span<const uint8_t> mask, double ssim_weight = 0.2);

}  // namespace vksplat::reference
