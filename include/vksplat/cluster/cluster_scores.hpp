#pragma once
// Per-cluster scores and the cluster selection of cluster pruning.
//   spatial variance: mean squared distance of the members from the cluster's centre;
//   depth variance:   per view, the variance of the view-space depth of the members visible in it,
//                     averaged over the views that see at least one member;
//   MVR (multi-view visibility ratio): (1 - w) * view_coverage + w * mean_visible_frac, with
//                     view_coverage the fraction of views that see at least one member and
//                     mean_visible_frac the mean over views of the fraction of members seen.
// The variances are normalised to [0, 1] by dividing by their 99th percentile over clusters and
// clamping (the raw values are heavy-tailed: a min-max scale would squash all but a few clusters
// to 0); MVR is a fraction already. G* = -alpha * spatial - beta * depth + gamma * MVR.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "vksplat/camera.hpp"
#include "vksplat/cluster/union_find.hpp"

namespace vksplat::cluster {

struct ScoreWeights {
    double alpha = 0.1;   // spatial variance
    double beta = 0.1;    // depth variance
    double gamma = 1.0;   // MVR
    double mvr_mean_frac_weight = 0.3;
};

struct ClusterScores {
    std::vector<double> spatial_raw, depth_raw;   // per cluster
    std::vector<double> spatial, depth, mvr;      // normalised to [0, 1]
    std::vector<double> score;                    // G*
    size_t size() const { return score.size(); }
};

// positions: 3 floats per Gaussian; cluster_of from build_clusters (ids 0..clusters-1);
// cameras: the views of `labels`, in its order. Throws InputError when the sizes disagree.
ClusterScores score_clusters(std::span<const float> positions, std::span<const int32_t> cluster_of,
                             const ViewLabels& labels, const std::vector<Camera>& cameras, const ScoreWeights& weights);

// Value at each of `percents` (0..100, linear interpolation) of `values`.
std::vector<double> percentiles(std::vector<double> values, const std::vector<double>& percents);
inline const std::vector<double> kReportPercents{0, 25, 50, 75, 90, 95, 100};

struct ClusterSelection {
    std::vector<uint8_t> keep;        // per Gaussian
    size_t clusters_dropped = 0;
    size_t gaussians_kept = 0;
    std::vector<std::string> warnings;
};

// Drops the clusters whose G* is below `threshold` when given, else the floor(ratio * clusters)
// clusters of lowest G* (ties: the higher cluster id goes first). Never drops every cluster: when
// a rule would, the best cluster stays and a warning says so.
ClusterSelection select_clusters(const ClusterScores& scores, std::span<const int32_t> cluster_of,
                                 std::optional<double> threshold, double ratio);

// Per Gaussian, the G* of its cluster: ranks Gaussians for a kept count (prune::select_count).
std::vector<float> gaussian_scores(const ClusterScores& scores, std::span<const int32_t> cluster_of);

}  // namespace vksplat::cluster
