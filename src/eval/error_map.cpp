#include "eval/image_args.hpp"
#include "vksplat/eval/metrics.hpp"

#include <cmath>

namespace vksplat::eval {

std::vector<float> error_map(const float* a, const float* b, int width, int height, int channels) {
    detail::check_image_pair("error_map", a, b, width, height, channels);
    const size_t pixels = detail::value_count(width, height, 1);
    std::vector<float> err(pixels);
    for (size_t p = 0; p < pixels; ++p) {
        double sum = 0.0;
        for (int ch = 0; ch < channels; ++ch) {
            const size_t i = p * channels + ch;
            sum += std::abs(detail::clamp01(a[i]) - detail::clamp01(b[i]));
        }
        err[p] = static_cast<float>(sum / channels);
    }
    return err;
}

}  // namespace vksplat::eval
