#pragma once
// Neighbouring Gaussians: pairs of centres closer than delta, found with a nanoflann KD-tree and
// handed over in batches, so memory stays bounded whatever delta is.
//
// Each centre is paired with at most max_neighbours of its nearest centres within delta; a pair
// comes as (lower index, higher index), twice when each end is among the other's nearest. The
// cap is what keeps a large delta from costing O(N^2) pairs and time: for the union-find that
// follows, a few nearest neighbours connect a dense region as well as all of them do. Memory
// does not grow with delta: beyond the tree (4 bytes of index per centre plus one node per 16
// centres), a batch's pairs take at most 8 * batch_size * (max_neighbours + 1) bytes, 8.5 MiB at
// the defaults.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <utility>
#include <vector>

namespace vksplat::cluster {

struct NeighbourParams {
    float delta = 0.01f;          // scene units
    size_t max_neighbours = 16;   // per centre, nearest first
    size_t batch_size = 65536;    // centres searched per batch
};

using Pair = std::pair<uint32_t, uint32_t>;
// Receives each batch of pairs; the span is valid only during the call.
using PairSink = std::function<void(std::span<const Pair>)>;

// Distances from centres to their nearest other centre, over a sample.
struct NearestDistanceStats {
    size_t sampled = 0;
    double median = 0, mean = 0, p95 = 0;
};

// positions: 3 floats per centre. Samples up to `sample` centres evenly spread over the index
// range (deterministic).
NearestDistanceStats nearest_distance_stats(std::span<const float> positions, size_t sample = 20000);
// The delta `auto` picks: twice the median nearest-neighbour distance, so that a typical centre
// reaches its nearest few neighbours while isolated floaters (beyond the median's reach) stay
// out. 0 when there are fewer than two centres.
double auto_delta(const NearestDistanceStats& stats);

// Streams every pair as described above, batch_size centres' worth at a time; returns how many
// pairs were reported.
size_t for_each_neighbour_pair(std::span<const float> positions, const NeighbourParams& params, const PairSink& sink);

}  // namespace vksplat::cluster
