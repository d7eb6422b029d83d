#include "support/image_compare.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace vksplat::test {

double ImageDiff::fraction_within(double tolerance) const {
    if (abs_errors.empty()) return 1.0;
    const auto n = std::count_if(abs_errors.begin(), abs_errors.end(), [&](float e) { return e <= tolerance; });
    return double(n) / double(abs_errors.size());
}

ImageDiff compare(const std::vector<float>& a, const std::vector<float>& b) {
    if (a.size() != b.size()) throw std::invalid_argument("compare: images differ in size");
    ImageDiff diff;
    diff.abs_errors.resize(a.size());
    double sum = 0, squared = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        const double e = std::abs(double(a[i]) - double(b[i]));
        diff.abs_errors[i] = float(e);
        sum += e;
        const double clamped = std::clamp(double(a[i]), 0.0, 1.0) - std::clamp(double(b[i]), 0.0, 1.0);
        squared += clamped * clamped;
        if (e > diff.max_abs || std::isnan(e)) {
            diff.max_abs = std::isnan(e) ? std::numeric_limits<double>::infinity() : e;
            diff.worst_index = i;
        }
    }
    const double n = a.empty() ? 1.0 : double(a.size());
    diff.mean_abs = sum / n;
    diff.psnr = squared == 0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(n / squared);
    return diff;
}

}  // namespace vksplat::test
