// Neighbour pairs through a nanoflann KD-tree, streamed in batches (see neighbours.hpp).
#include "vksplat/cluster/neighbours.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "scene/point_tree.hpp"

namespace vksplat::cluster {

NearestDistanceStats nearest_distance_stats(std::span<const float> positions, size_t sample) {
    const size_t n = positions.size() / 3;
    NearestDistanceStats stats;
    if (n < 2 || sample == 0) return stats;
    const PointSpan centres{positions};
    const PointTree tree(3, centres, nanoflann::KDTreeSingleIndexAdaptorParams(16));
    const size_t count = std::min(sample, n);
    std::vector<double> distances;
    distances.reserve(count);
    for (size_t s = 0; s < count; ++s) {
        const size_t i = s * n / count;
        uint32_t index[2];
        float squared[2];
        const size_t found = tree.knnSearch(&positions[i * 3], 2, index, squared);
        // The nearest result is the centre itself (or a duplicate at distance 0, which counts).
        if (found == 2) distances.push_back(std::sqrt(double(squared[1])));
    }
    stats.sampled = distances.size();
    if (distances.empty()) return stats;
    stats.mean = std::accumulate(distances.begin(), distances.end(), 0.0) / double(distances.size());
    std::sort(distances.begin(), distances.end());
    auto at = [&](double fraction) { return distances[size_t(std::lround(fraction * double(distances.size() - 1)))]; };
    stats.median = at(0.5);
    stats.p95 = at(0.95);
    return stats;
}

double auto_delta(const NearestDistanceStats& stats) { return 2.0 * stats.median; }

size_t for_each_neighbour_pair(std::span<const float> positions, const NeighbourParams& params, const PairSink& sink) {
    const size_t n = positions.size() / 3;
    if (n < 2 || params.max_neighbours == 0 || !(params.delta > 0)) return 0;
    const PointSpan centres{positions};
    const PointTree tree(3, centres, nanoflann::KDTreeSingleIndexAdaptorParams(16));
    const size_t k = std::min(params.max_neighbours + 1, n);  // +1: the centre finds itself
    const float delta_squared = params.delta * params.delta;
    const size_t batch = std::max<size_t>(1, params.batch_size);
    std::vector<uint32_t> index(k);
    std::vector<float> squared(k);
    std::vector<Pair> pairs;
    pairs.reserve(batch * k);
    size_t total = 0;
    for (size_t start = 0; start < n; start += batch) {
        pairs.clear();
        const size_t end = std::min(n, start + batch);
        for (size_t i = start; i < end; ++i) {
            const size_t found = tree.knnSearch(&positions[i * 3], k, index.data(), squared.data());
            for (size_t r = 0; r < found; ++r) {
                if (squared[r] > delta_squared) break;  // results come nearest first
                const uint32_t j = index[r];
                if (j == i) continue;
                // Found from both ends when each is among the other's nearest: reported twice
                // then, which costs union-find one lookup; deduplicating would cost a set.
                pairs.emplace_back(std::min<uint32_t>(uint32_t(i), j), std::max<uint32_t>(uint32_t(i), j));
            }
        }
        total += pairs.size();
        sink(pairs);
    }
    return total;
}

}  // namespace vksplat::cluster
