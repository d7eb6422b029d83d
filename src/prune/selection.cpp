// Keep masks from scores: threshold, count and ratio on top of the lossless pass.
#include "vksplat/prune/selection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

#include "vksplat/error.hpp"

namespace vksplat::prune {
namespace {

void check_sizes(size_t scores, size_t candidates) {
    if (scores != candidates)
        throw std::invalid_argument("prune selection: " + std::to_string(scores) + " scores for a mask of " +
                                    std::to_string(candidates) + " Gaussians");
    if (scores > std::numeric_limits<uint32_t>::max())
        throw std::invalid_argument("prune selection: more than 2^32 Gaussians");
}

}  // namespace

KeepMask keep_all(size_t n) { return KeepMask(n, 1); }

KeepMask lossless_mask(const ViewTotals& totals) {
    KeepMask keep(totals.size());
    for (size_t i = 0; i < keep.size(); ++i) keep[i] = totals.pixels[i] > 0;
    return keep;
}

size_t count_kept(std::span<const uint8_t> keep) {
    return size_t(std::count_if(keep.begin(), keep.end(), [](uint8_t k) { return k != 0; }));
}

Ranking::Ranking(std::span<const float> scores, std::span<const uint8_t> candidates) : size_(scores.size()) {
    check_sizes(scores.size(), candidates.size());
    for (size_t i = 0; i < candidates.size(); ++i)
        if (candidates[i]) order_.push_back(uint32_t(i));
    // A total order (indices are unique), so std::sort is as deterministic as a stable sort.
    std::sort(order_.begin(), order_.end(), [&](uint32_t a, uint32_t b) {
        const bool nan_a = std::isnan(scores[a]), nan_b = std::isnan(scores[b]);
        if (nan_a != nan_b) return nan_b;
        if (!nan_a && scores[a] != scores[b]) return scores[a] > scores[b];
        return a < b;
    });
}

KeepMask Ranking::keep_best(size_t count) const {
    KeepMask keep(size_, 0);
    const size_t n = std::min(count, order_.size());
    for (size_t k = 0; k < n; ++k) keep[order_[k]] = 1;
    return keep;
}

std::vector<float> sampling_keys(std::span<const float> scores, uint64_t seed) {
    std::mt19937_64 bits(seed);
    std::vector<float> keys(scores.size());
    for (size_t i = 0; i < keys.size(); ++i) {
        // 53 random bits, centred in their interval: u lies strictly inside (0, 1), so ln(u) < 0.
        const double u = (double(bits() >> 11) + 0.5) * 0x1p-53;
        const float w = scores[i];
        keys[i] = std::isnan(w) ? w : w > 0 ? float(std::log(u) / double(w)) : -std::numeric_limits<float>::infinity();
    }
    return keys;
}

KeepMask select_threshold(std::span<const float> scores, float threshold, std::span<const uint8_t> candidates) {
    check_sizes(scores.size(), candidates.size());
    KeepMask keep(scores.size());
    for (size_t i = 0; i < keep.size(); ++i) keep[i] = candidates[i] && scores[i] > threshold;
    return keep;
}

KeepMask select_ratio(std::span<const float> scores, double ratio, std::span<const uint8_t> candidates) {
    if (!(ratio >= 0.0 && ratio <= 1.0))
        throw InputError("ratio " + std::to_string(ratio), "must lie in [0, 1] (the fraction of Gaussians to drop)");
    const size_t n = scores.size();
    const size_t drop = std::min(n, size_t(std::llround(ratio * double(n))));
    return select_count(scores, n - drop, candidates);
}

KeepMask select_count(std::span<const float> scores, size_t keep, std::span<const uint8_t> candidates) {
    return Ranking(scores, candidates).keep_best(keep);
}

}  // namespace vksplat::prune
