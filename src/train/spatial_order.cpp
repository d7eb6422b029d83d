#include "train/spatial_order.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace vksplat::train {
namespace {

// The 21 bits of v spread to every third bit of 63.
uint64_t spread_bits(uint64_t v) {
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffull;
    v = (v | v << 16) & 0x1f0000ff0000ffull;
    v = (v | v << 8) & 0x100f00f00f00f00full;
    v = (v | v << 4) & 0x10c30c30c30c30c3ull;
    v = (v | v << 2) & 0x1249249249249249ull;
    return v;
}

}  // namespace

std::vector<uint32_t> morton_order(const float* positions, uint32_t count) {
    float low[3], high[3];
    std::fill(low, low + 3, std::numeric_limits<float>::infinity());
    std::fill(high, high + 3, -std::numeric_limits<float>::infinity());
    const auto finite = [&](uint32_t i) {
        return std::isfinite(positions[3 * i]) && std::isfinite(positions[3 * i + 1]) && std::isfinite(positions[3 * i + 2]);
    };
    for (uint32_t i = 0; i < count; ++i)
        if (finite(i))
            for (int k = 0; k < 3; ++k) {
                low[k] = std::min(low[k], positions[3 * i + k]);
                high[k] = std::max(high[k], positions[3 * i + k]);
            }
    std::vector<uint64_t> code(count, std::numeric_limits<uint64_t>::max());
    for (uint32_t i = 0; i < count; ++i) {
        if (!finite(i)) continue;
        code[i] = 0;
        for (int k = 0; k < 3; ++k) {
            const double extent = double(high[k]) - double(low[k]);
            const double unit = extent > 0 ? (double(positions[3 * i + k]) - low[k]) / extent : 0.0;
            code[i] |= spread_bits(uint64_t(std::clamp(unit, 0.0, 1.0) * 2097151.0)) << k;
        }
    }
    std::vector<uint32_t> order(count);
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return code[a] < code[b]; });
    return order;
}

}  // namespace vksplat::train
