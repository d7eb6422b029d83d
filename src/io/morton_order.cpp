#include "io/morton_order.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

namespace vksplat::io::detail {
namespace {

// The low 21 bits of `v`, two zero bits after each.
uint64_t spread_three(uint64_t v) {
    v &= 0x1fffff;
    v = (v | v << 32) & 0x001f00000000ffffull;
    v = (v | v << 16) & 0x001f0000ff0000ffull;
    v = (v | v << 8) & 0x100f00f00f00f00full;
    v = (v | v << 4) & 0x10c30c30c30c30c3ull;
    v = (v | v << 2) & 0x1249249249249249ull;
    return v;
}

}  // namespace

// splat-transform uses 10 bits an axis and re-sorts any run of more than 256 equal codes;
// 21 bits reach the same order in one pass.
std::vector<size_t> morton_order(const GaussianCloud& cloud) {
    const size_t n = cloud.size();
    float low[3], high[3];
    std::fill(low, low + 3, INFINITY);
    std::fill(high, high + 3, -INFINITY);
    for (size_t i = 0; i < n; ++i)
        for (size_t a = 0; a < 3; ++a) {
            low[a] = std::min(low[a], cloud.positions[i * 3 + a]);
            high[a] = std::max(high[a], cloud.positions[i * 3 + a]);
        }
    constexpr double kCells = double(1 << 21);
    std::vector<uint64_t> code(n);
    for (size_t i = 0; i < n; ++i)
        for (size_t a = 0; a < 3; ++a) {
            const double extent = double(high[a]) - low[a];
            const double cell = extent > 0 ? (cloud.positions[i * 3 + a] - double(low[a])) / extent * kCells : 0.0;
            code[i] |= spread_three(static_cast<uint64_t>(std::clamp(cell, 0.0, kCells - 1))) << a;
        }
    std::vector<size_t> order(n);
    std::iota(order.begin(), order.end(), size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return code[a] < code[b]; });
    return order;
}

}  // namespace vksplat::io::detail
