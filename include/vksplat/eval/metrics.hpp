#pragma once
// Image-quality metrics for comparing a render with a reference picture.
//
// Images are float, row-major, `channels` interleaved values per pixel (RGB for 3), nominally in
// [0, 1]. Every function clamps values to [0, 1] before comparing: a saved picture can hold nothing
// else, so over- or under-shoot that would vanish on saving must not count as error. NaN is not
// clamped: a NaN pixel makes PSNR and SSIM NaN, so a broken render cannot pass unnoticed.
// Sizes that are not positive, or null pointers, throw std::invalid_argument.
#include <cstdint>
#include <vector>

namespace vksplat::eval {

// Peak signal-to-noise ratio in dB with a peak of 1: 10 * log10(1 / MSE), the MSE taken over every
// value of every channel. Identical images (MSE = 0) give +infinity; callers that average PSNR over
// views should decide what that means for them rather than get an arbitrary large number.
// Matches skimage.metrics.peak_signal_noise_ratio(a, b, data_range=1).
double psnr(const float* a, const float* b, int width, int height, int channels = 3);

// Structural similarity (Wang et al. 2004): an 11 x 11 Gaussian window with sigma = 1.5,
// C1 = 0.01^2, C2 = 0.03^2, population (not sample) covariances, computed per channel and averaged
// over channels and over the pixels of the *valid* region only: the pixels at least 5 from every
// border, whose window lies wholly inside the image. No padding is involved.
// This is exactly skimage.metrics.structural_similarity(a, b, channel_axis=2, data_range=1,
// gaussian_weights=True, sigma=1.5, use_sample_covariance=False): skimage filters with 'reflect'
// borders but then crops the 5-pixel border, which leaves the valid convolution.
// (The 3DGS repository's PyTorch ssim instead zero-pads and averages all pixels; its numbers are
// slightly lower near the borders, so compare SSIM only between tables made with one definition.)
// Both sides must be at least 11 pixels; smaller images throw std::invalid_argument.
double ssim(const float* a, const float* b, int width, int height, int channels = 3);

// The same two over a region: `mask` holds width * height bytes, non-zero where a pixel counts.
// masked_psnr takes the MSE over those pixels' values; masked_ssim averages the SSIM map over the
// valid-region pixels in the mask (the windows still read their unmasked neighbours: SSIM is a
// statement about a pixel's surroundings). NaN when no pixel counts; a null mask throws.
double masked_psnr(const float* a, const float* b, const uint8_t* mask, int width, int height, int channels = 3);
double masked_ssim(const float* a, const float* b, const uint8_t* mask, int width, int height, int channels = 3);

// Per-pixel error: the mean over channels of |a - b|, width * height values, row-major.
std::vector<float> error_map(const float* a, const float* b, int width, int height, int channels = 3);

// Colours an error map for viewing: err / max_value, clamped to [0, 1], through the perceptually
// uniform 'inferno' ramp (black - purple - orange - pale yellow). Writes 3 bytes (R, G, B) per
// value into rgb_out, resized to fit. NaN errors are shown at the top of the ramp, as a defect
// should be. max_value must be positive and finite.
void colorize_heat(const std::vector<float>& err, float max_value, std::vector<uint8_t>& rgb_out);

}  // namespace vksplat::eval
