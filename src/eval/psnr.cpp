#include "eval/image_args.hpp"
#include "vksplat/eval/metrics.hpp"

#include <cmath>

namespace vksplat::eval {

double psnr(const float* a, const float* b, int width, int height, int channels) {
    detail::check_image_pair("psnr", a, b, width, height, channels);
    const size_t n = detail::value_count(width, height, channels);
    // Double accumulation: a float sum of ~10^6 squared errors would lose the digits PSNR reports.
    double sum = 0.0;
    for (size_t i = 0; i < n; ++i) {
        const double d = detail::clamp01(a[i]) - detail::clamp01(b[i]);
        sum += d * d;
    }
    const double mse = sum / static_cast<double>(n);
    if (mse == 0.0) return INFINITY;
    return 10.0 * std::log10(1.0 / mse);
}

}  // namespace vksplat::eval
