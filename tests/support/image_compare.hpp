#pragma once
// Differences between two float images (same size, same channel count).
#include <cstddef>
#include <vector>

namespace vksplat::test {

struct ImageDiff {
    double max_abs = 0;
    double mean_abs = 0;
    double psnr = 0;             // over values clamped to [0, 1]; +inf when identical
    size_t worst_index = 0;      // value index of max_abs
    double fraction_within(double tolerance) const;
    std::vector<float> abs_errors;
};

ImageDiff compare(const std::vector<float>& a, const std::vector<float>& b);

}  // namespace vksplat::test
