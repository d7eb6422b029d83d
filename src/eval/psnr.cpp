#include "eval/image_args.hpp"
#include "vksplat/eval/metrics.hpp"

#include <cmath>
#include <stdexcept>

namespace vksplat::eval {
namespace {

double psnr_of_mse(double mse) { return mse == 0.0 ? INFINITY : 10.0 * std::log10(1.0 / mse); }

}  // namespace

double psnr(const float* a, const float* b, int width, int height, int channels) {
    detail::check_image_pair("psnr", a, b, width, height, channels);
    const size_t n = detail::value_count(width, height, channels);
    // Double accumulation: a float sum of ~10^6 squared errors would lose the digits PSNR reports.
    double sum = 0.0;
    for (size_t i = 0; i < n; ++i) {
        const double d = detail::clamp01(a[i]) - detail::clamp01(b[i]);
        sum += d * d;
    }
    return psnr_of_mse(sum / static_cast<double>(n));
}

double masked_psnr(const float* a, const float* b, const uint8_t* mask, int width, int height, int channels) {
    detail::check_image_pair("masked_psnr", a, b, width, height, channels);
    if (!mask) throw std::invalid_argument("masked_psnr: null mask");
    const size_t pixels = detail::value_count(width, height, 1);
    double sum = 0.0;
    size_t counted = 0;
    for (size_t p = 0; p < pixels; ++p) {
        if (!mask[p]) continue;
        for (int c = 0; c < channels; ++c) {
            const size_t i = p * channels + c;
            const double d = detail::clamp01(a[i]) - detail::clamp01(b[i]);
            sum += d * d;
        }
        counted += channels;
    }
    if (counted == 0) return NAN;
    return psnr_of_mse(sum / static_cast<double>(counted));
}

}  // namespace vksplat::eval
