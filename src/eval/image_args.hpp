#pragma once
// Checks and clamping that every metric shares, so each one validates its inputs the same way.
#include <algorithm>
#include <cstddef>

namespace vksplat::eval::detail {

// Throws std::invalid_argument, naming `metric`, for null images or non-positive sizes.
void check_image_pair(const char* metric, const float* a, const float* b, int width, int height,
                      int channels);

// What a saved picture would hold. NaN passes through so that a broken render is not hidden.
inline double clamp01(float v) { return std::clamp(static_cast<double>(v), 0.0, 1.0); }

inline size_t value_count(int width, int height, int channels) {
    return static_cast<size_t>(width) * static_cast<size_t>(height) * static_cast<size_t>(channels);
}

}  // namespace vksplat::eval::detail
