#pragma once
// From scores to a keep mask (keep[i] != 0: Gaussian i stays), the form GaussianCloud::subset takes.
//
// Every selector works on `candidates`, the Gaussians still in play, normally lossless_mask(totals):
// the lossless pass drops first, whatever the method, the Gaussians that reached alpha >= 1/255 on
// no pixel of any view accumulated, which leaves those views' renders bit-identical. What a
// selector drops is on top of that. Counts and ratios always refer to the original number of
// Gaussians N (the mask's size):
//   - select_threshold: keeps the candidates whose score is above T (drops score <= T).
//   - select_count(K): keeps the K candidates of highest score; all candidates when there are no
//     more than K (so keep > N, or a lossless pass that already dropped N - K or more, keeps every
//     candidate).
//   - select_ratio(R), R in [0, 1]: drops round(R * N) of the N Gaussians, i.e. select_count with
//     K = N - round(R * N). Where the lossless pass alone dropped more than that, only its drop
//     happens.
// Order and ties: a Gaussian ranks by score, equal scores by index (the lower index is kept
// first), and a NaN score ranks below everything, so every selection is deterministic.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "vksplat/prune/accumulate.hpp"

namespace vksplat::prune {

using KeepMask = std::vector<uint8_t>;

// All n kept.
KeepMask keep_all(size_t n);
// Kept where the Gaussian reached alpha >= 1/255 on at least one pixel of the accumulated views.
KeepMask lossless_mask(const ViewTotals& totals);
size_t count_kept(std::span<const uint8_t> keep);

// The candidates ordered from most to least worth keeping: the best K of them, for any K, without
// sorting again (what a bisection on the kept count needs).
class Ranking {
public:
    // Throws std::invalid_argument when the sizes differ.
    Ranking(std::span<const float> scores, std::span<const uint8_t> candidates);
    size_t candidates() const { return order_.size(); }
    size_t size() const { return size_; }
    // The best min(count, candidates()) candidates.
    KeepMask keep_best(size_t count) const;

private:
    std::vector<uint32_t> order_;  // candidate indices, best first
    size_t size_ = 0;
};

// Scores turned into keys whose ranking is a weighted random sample without replacement: ranked
// by these keys, the best K are K Gaussians drawn one after another with probability proportional
// to their score among those not drawn yet (Efraimidis and Spirakis 2006: key = ln(u) / score,
// u uniform in (0, 1) from `seed`). Mini-Splatting (Fang and Wang 2024) simplifies a scene by
// sampling on its importance rather than keeping the top: a region of many faint Gaussians keeps
// a few of them instead of none, for the re-fit to grow. Scores <= 0 rank last, NaN below them;
// the same seed gives the same keys on every platform (std::mt19937_64, no std:: distribution).
std::vector<float> sampling_keys(std::span<const float> scores, uint64_t seed);

KeepMask select_threshold(std::span<const float> scores, float threshold, std::span<const uint8_t> candidates);
// Throws InputError for a ratio outside [0, 1] (or NaN).
KeepMask select_ratio(std::span<const float> scores, double ratio, std::span<const uint8_t> candidates);
KeepMask select_count(std::span<const float> scores, size_t keep, std::span<const uint8_t> candidates);

}  // namespace vksplat::prune
