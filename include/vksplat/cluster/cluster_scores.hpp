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
// to 0); MVR is a fraction already.
//   contribution:     what the cluster's members paint in the views: per Gaussian, the share of a
//                     view's pixels it blends into (sum of alpha * T over the pixels / pixels),
//                     averaged over the views; per cluster, the largest over its members,
//                     normalised like the variances.
//   centrality:       how much the views look at the members (cluster/centrality.hpp): the mean
//                     over members of their centrality, a fraction already. A cluster is central
//                     when it reaches central_threshold; G* adds lambda to central clusters only.
// G* = -alpha * spatial - beta * depth + gamma * MVR + kappa * contribution + lambda * [central].
//
// Why a step and not lambda * centrality: centrality tells subject from background, not the
// subject's parts apart. Added as a slope it ranked the subject's edges (the table's rim in
// bonsai) below faint splats in its middle, and dropped them whole (bonsai, 85% dropped: subject
// 20.6 dB with the slope, 24.8 dB with the step, unpruned 28.3). Why 0.25: in a capture circling a
// subject, the subject scores over 0.5 and the room under 0.2 (bonsai: 78% of the Gaussians under
// 0.16, 18% over 0.6); in an object-centred capture nothing scores under it (lego's least
// central Gaussian: 0.37), so the step changes nothing there.
//
// Why the contribution term: the original G* (kappa = 0) has no term for what a cluster adds to
// the picture. In trained scenes the clusters that stay single are mostly the large Gaussians that
// fill surfaces, and they score lowest on MVR, so dropping the lowest G* first removed the
// surfaces (snowmiku: subject PSNR 29.4 -> 8.3 dB). And MVR does not help once contribution is
// there: on lego, G* with both dropped clusters that paint the subject first. So the defaults
// weigh contribution alone (alpha = beta = gamma = lambda = 0): they keep the whole picture. To
// keep the subject and drop the room, lambda 1 lifts every central cluster above every other and
// contribution orders within each (bonsai, 80% dropped: subject -0.09 dB). Not the default: where
// the drop is capped by what the picture loses, dropping the room first costs the picture more
// (snowmiku at the defaults: whole picture -0.14 dB and 14.9% dropped by contribution alone,
// -0.20 dB and 13.5% with the step, which keeps the subject exactly). The weights are one flag each away.
// The largest member rather than the mean or the sum: a cluster goes whole, so it is worth what its
// most visible member paints. The mean let one painting splat go with many faint neighbours (lego,
// 10% of the Gaussians dropped: subject -3.5 dB by the mean, -2.8 dB by the largest); the sum
// ranks every single splat below every large cluster.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "vksplat/camera/camera.hpp"
#include "vksplat/cluster/union_find.hpp"

namespace vksplat::cluster {

// The defaults weigh contribution alone (see above). The G*: alpha 0.1, beta 0.1, gamma 1,
// kappa 0 (kOriginalWeights).
struct ScoreWeights {
    double alpha = 0.0;   // spatial variance
    double beta = 0.0;    // depth variance
    double gamma = 0.0;   // MVR
    double mvr_mean_frac_weight = 0.3;
    double kappa = 1.0;   // contribution
    double lambda = 0.0;  // central (centrality >= central_threshold)
    double central_threshold = 0.25;
};
inline constexpr ScoreWeights kOriginalWeights{.alpha = 0.1, .beta = 0.1, .gamma = 1.0, .mvr_mean_frac_weight = 0.3,
                                               .kappa = 0.0, .lambda = 0.0};

struct ClusterScores {
    std::vector<double> spatial_raw, depth_raw;   // per cluster
    std::vector<double> contribution_raw;         // per cluster: the sum over its members
    std::vector<size_t> members;                  // per cluster
    std::vector<double> spatial, depth, mvr;      // normalised to [0, 1]
    std::vector<double> contribution;             // largest member's, normalised to [0, 1]
    std::vector<double> centrality;               // mean over members, in [0, 1]
    std::vector<double> score;                    // G*
    size_t size() const { return score.size(); }
};

// positions: 3 floats per Gaussian; cluster_of from build_clusters (ids 0..clusters-1);
// cameras: the views of `labels`, in its order; contribution: per Gaussian, its mean share of
// the views' pixels (jobs::ProjectedViews::contribution), or empty when kappa is 0. Throws InputError
// when the sizes disagree.
ClusterScores score_clusters(std::span<const float> positions, std::span<const int32_t> cluster_of,
                             const ViewLabels& labels, const std::vector<Camera>& cameras, const ScoreWeights& weights,
                             std::span<const float> contribution = {});

// Value at each of `percents` (0..100, linear interpolation) of `values`.
std::vector<double> percentiles(std::vector<double> values, const std::vector<double>& percents);
inline const std::vector<double> kReportPercents{0, 25, 50, 75, 90, 95, 100};

struct ClusterSelection {
    std::vector<uint8_t> keep;        // per Gaussian
    size_t clusters_dropped = 0;
    size_t gaussians_kept = 0;
    double contribution_dropped = 0;  // share of the scene's total contribution (0 without one)
    bool stopped_by_contribution = false;  // max_contribution_loss ended the drop before the ratio
    std::vector<std::string> warnings;
};

// What the prune ratio counts. gaussians: whole clusters, lowest G* first, are dropped until at
// least round(ratio * Gaussians) are gone (the last cluster may overshoot). clusters: the
// floor(ratio * clusters) clusters of lowest G* (the original rule; with trained scenes' many
// single-Gaussian clusters it drops far more of the picture than the ratio suggests).
enum class RatioOf { gaussians, clusters };
// "gaussians" or "clusters"; throws InputError otherwise.
RatioOf parse_ratio_of(const std::string& name);
std::string to_string(RatioOf unit);

struct SelectionRule {
    std::optional<double> threshold;  // drop G* < threshold when given (the ratio is then unused)
    double ratio = 0.5;
    RatioOf ratio_of = RatioOf::gaussians;
    // Stop before a cluster whose drop would take the dropped clusters' summed contribution above
    // this share of the scene's total (1: no limit). Needs scores.contribution_raw.
    double max_contribution_loss = 1.0;
};

// Drops clusters in order of G* (ties: the higher cluster id goes first) under `rule`. Never drops
// every cluster: when a rule would, the best cluster stays and a warning says so.
ClusterSelection select_clusters(const ClusterScores& scores, std::span<const int32_t> cluster_of,
                                 const SelectionRule& rule);

// Per Gaussian, the G* of its cluster: ranks Gaussians for a kept count (prune::select_count).
std::vector<float> gaussian_scores(const ClusterScores& scores, std::span<const int32_t> cluster_of);

}  // namespace vksplat::cluster
