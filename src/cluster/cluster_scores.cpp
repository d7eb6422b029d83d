// Per-cluster scores, percentiles and the cluster selection (see cluster_scores.hpp).
#include "vksplat/cluster/cluster_scores.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "vksplat/cluster/centrality.hpp"
#include "vksplat/cluster/region_map.hpp"
#include "vksplat/error.hpp"

namespace vksplat::cluster {
namespace {

// value / (99th percentile), clamped to [0, 1]; the maximum stands in when the percentile is 0.
std::vector<double> normalise(const std::vector<double>& raw) {
    std::vector<double> out(raw.size(), 0.0);
    if (raw.empty()) return out;
    double scale = percentiles(raw, {99.0})[0];
    if (!(scale > 0)) scale = *std::max_element(raw.begin(), raw.end());
    if (!(scale > 0)) return out;
    for (size_t c = 0; c < raw.size(); ++c) out[c] = std::clamp(raw[c] / scale, 0.0, 1.0);
    return out;
}

}  // namespace

std::vector<double> percentiles(std::vector<double> values, const std::vector<double>& percents) {
    std::vector<double> out(percents.size(), 0.0);
    if (values.empty()) return out;
    std::sort(values.begin(), values.end());
    for (size_t k = 0; k < percents.size(); ++k) {
        const double position = std::clamp(percents[k], 0.0, 100.0) / 100.0 * double(values.size() - 1);
        const size_t below = size_t(std::floor(position));
        const size_t above = std::min(below + 1, values.size() - 1);
        out[k] = values[below] + (values[above] - values[below]) * (position - double(below));
    }
    return out;
}

RatioOf parse_ratio_of(const std::string& name) {
    if (name == "gaussians") return RatioOf::gaussians;
    if (name == "clusters") return RatioOf::clusters;
    throw InputError("prune ratio unit '" + name + "'", "expected gaussians or clusters");
}

std::string to_string(RatioOf unit) { return unit == RatioOf::gaussians ? "gaussians" : "clusters"; }

ClusterScores score_clusters(std::span<const float> positions, std::span<const int32_t> cluster_of,
                             const ViewLabels& labels, const std::vector<Camera>& cameras, const ScoreWeights& weights,
                             std::span<const float> contribution) {
    const size_t n = cluster_of.size();
    if (positions.size() != n * 3 || labels.gaussians != n || labels.ids.size() != labels.views * n)
        throw InputError("cluster scores", "positions, cluster ids and view labels disagree in size");
    if (!contribution.empty() && contribution.size() != n)
        throw InputError("cluster scores", std::to_string(contribution.size()) + " contributions for " +
                                               std::to_string(n) + " Gaussians");
    if (contribution.empty() && weights.kappa != 0)
        throw InputError("cluster scores", "the contribution term (kappa) needs each Gaussian's contribution; "
                                           "give kappa 0 for the original G*");
    if (cameras.size() != labels.views)
        throw InputError("cluster scores", std::to_string(cameras.size()) + " cameras for " +
                                               std::to_string(labels.views) + " views of labels");
    size_t clusters = 0;
    for (int32_t c : cluster_of) {
        if (c < 0) throw InputError("cluster ids", "hold a negative id");
        clusters = std::max(clusters, size_t(c) + 1);
    }

    // Spatial variance from per-cluster sums (double: scene coordinates are small).
    std::vector<double> count(clusters, 0), sum(clusters * 3, 0), sum_squared(clusters, 0);
    for (size_t g = 0; g < n; ++g) {
        const size_t c = size_t(cluster_of[g]);
        count[c] += 1;
        for (int d = 0; d < 3; ++d) {
            const double p = positions[g * 3 + d];
            sum[c * 3 + d] += p;
            sum_squared[c] += p * p;
        }
    }
    ClusterScores s;
    s.members.assign(clusters, 0);
    s.contribution_raw.assign(clusters, 0);
    for (size_t g = 0; g < n; ++g) {
        s.members[size_t(cluster_of[g])] += 1;
        if (!contribution.empty()) s.contribution_raw[size_t(cluster_of[g])] += double(contribution[g]);
    }
    s.spatial_raw.assign(clusters, 0);
    for (size_t c = 0; c < clusters; ++c) {
        double centre_squared = 0;
        for (int d = 0; d < 3; ++d) centre_squared += (sum[c * 3 + d] / count[c]) * (sum[c * 3 + d] / count[c]);
        s.spatial_raw[c] = std::max(0.0, sum_squared[c] / count[c] - centre_squared);
    }

    // Per view: depth moments and visible counts of each cluster's visible members.
    std::vector<double> depth_sum(clusters, 0), depth_views(clusters, 0), covered(clusters, 0), visible_frac(clusters, 0);
    std::vector<double> seen(clusters), z_sum(clusters), z_squared(clusters);
    for (size_t v = 0; v < labels.views; ++v) {
        std::fill(seen.begin(), seen.end(), 0.0);
        std::fill(z_sum.begin(), z_sum.end(), 0.0);
        std::fill(z_squared.begin(), z_squared.end(), 0.0);
        const Camera& camera = cameras[v];
        for (size_t g = 0; g < n; ++g) {
            if (labels.at(v, g) == kNoRegion) continue;
            const size_t c = size_t(cluster_of[g]);
            const double z = camera.to_camera({positions[g * 3], positions[g * 3 + 1], positions[g * 3 + 2]}).z;
            seen[c] += 1;
            z_sum[c] += z;
            z_squared[c] += z * z;
        }
        for (size_t c = 0; c < clusters; ++c) {
            if (seen[c] == 0) continue;
            const double mean = z_sum[c] / seen[c];
            depth_sum[c] += std::max(0.0, z_squared[c] / seen[c] - mean * mean);
            depth_views[c] += 1;
            covered[c] += 1;
            visible_frac[c] += seen[c] / count[c];
        }
    }
    s.depth_raw.assign(clusters, 0);
    s.mvr.assign(clusters, 0);
    const double views = double(std::max<size_t>(1, labels.views));
    const double w = std::clamp(weights.mvr_mean_frac_weight, 0.0, 1.0);
    for (size_t c = 0; c < clusters; ++c) {
        if (depth_views[c] > 0) s.depth_raw[c] = depth_sum[c] / depth_views[c];
        s.mvr[c] = (1.0 - w) * covered[c] / views + w * visible_frac[c] / views;
    }
    s.spatial = normalise(s.spatial_raw);
    s.depth = normalise(s.depth_raw);
    std::vector<double> largest(clusters, 0.0);
    for (size_t g = 0; g < contribution.size(); ++g)
        largest[size_t(cluster_of[g])] = std::max(largest[size_t(cluster_of[g])], double(contribution[g]));
    s.contribution = normalise(largest);
    s.centrality.assign(clusters, 0.0);
    const std::vector<float> centrality = view_centrality(positions, cameras);
    for (size_t g = 0; g < n; ++g) s.centrality[size_t(cluster_of[g])] += centrality[g];
    for (size_t c = 0; c < clusters; ++c) s.centrality[c] /= count[c];
    s.score.resize(clusters);
    for (size_t c = 0; c < clusters; ++c)
        s.score[c] = -weights.alpha * s.spatial[c] - weights.beta * s.depth[c] + weights.gamma * s.mvr[c] +
                     weights.kappa * s.contribution[c] + weights.lambda * (s.centrality[c] >= weights.central_threshold ? 1.0 : 0.0);
    return s;
}

ClusterSelection select_clusters(const ClusterScores& scores, std::span<const int32_t> cluster_of,
                                 const SelectionRule& rule) {
    const size_t clusters = scores.size();
    if (!(rule.ratio >= 0.0 && rule.ratio <= 1.0)) throw InputError("prune ratio", "must lie in [0, 1]");
    if (!(rule.max_contribution_loss >= 0.0 && rule.max_contribution_loss <= 1.0))
        throw InputError("max contribution loss", "must lie in [0, 1]");
    const bool capped = rule.max_contribution_loss < 1.0;
    if (capped && scores.contribution_raw.size() != clusters)
        throw InputError("max contribution loss", "needs the clusters' contributions (score them again)");
    std::vector<size_t> members(clusters, 0);
    for (int32_t c : cluster_of) members[size_t(c)] += 1;
    ClusterSelection out;
    // Clusters from worst to best; ties: the higher id goes first, so the order is deterministic.
    std::vector<uint32_t> order(clusters);
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        return scores.score[a] != scores.score[b] ? scores.score[a] < scores.score[b] : a > b;
    });
    // The clusters the rule would drop, worst first.
    std::vector<uint32_t> candidates;
    if (rule.threshold) {
        for (uint32_t c : order)
            if (scores.score[c] < *rule.threshold) candidates.push_back(c);
    } else if (rule.ratio_of == RatioOf::clusters) {
        const size_t drop = size_t(std::floor(rule.ratio * double(clusters)));
        candidates.assign(order.begin(), order.begin() + std::ptrdiff_t(drop));
        if (rule.ratio > 0 && drop == 0 && clusters > 0)
            out.warnings.push_back("only " + std::to_string(clusters) + " cluster(s): a ratio of " +
                                   std::to_string(rule.ratio) + " drops none of them");
    } else {
        const size_t target = size_t(std::llround(rule.ratio * double(cluster_of.size())));
        size_t dropped = 0;
        for (size_t k = 0; k < order.size() && dropped < target; ++k) {
            candidates.push_back(order[k]);
            dropped += members[order[k]];
        }
    }
    const double total = std::accumulate(scores.contribution_raw.begin(), scores.contribution_raw.end(), 0.0);
    std::vector<uint8_t> keep_cluster(clusters, 1);
    double lost = 0;
    for (uint32_t c : candidates) {
        const double share = total > 0 && c < scores.contribution_raw.size() ? scores.contribution_raw[c] / total : 0.0;
        if (capped && lost + share > rule.max_contribution_loss) {
            out.stopped_by_contribution = true;
            break;
        }
        keep_cluster[c] = 0;
        lost += share;
    }
    if (clusters > 0 && std::none_of(keep_cluster.begin(), keep_cluster.end(), [](uint8_t k) { return k != 0; })) {
        keep_cluster[order.back()] = 1;
        if (total > 0) lost -= scores.contribution_raw[order.back()] / total;
        out.warnings.push_back("the selection would drop every cluster; kept the best one");
    }
    out.contribution_dropped = lost;
    out.clusters_dropped = size_t(std::count(keep_cluster.begin(), keep_cluster.end(), 0));
    out.keep.resize(cluster_of.size());
    for (size_t g = 0; g < cluster_of.size(); ++g) {
        out.keep[g] = keep_cluster[size_t(cluster_of[g])];
        out.gaussians_kept += out.keep[g];
    }
    return out;
}

std::vector<float> gaussian_scores(const ClusterScores& scores, std::span<const int32_t> cluster_of) {
    std::vector<float> out(cluster_of.size());
    for (size_t g = 0; g < cluster_of.size(); ++g) out[g] = float(scores.score[size_t(cluster_of[g])]);
    return out;
}

}  // namespace vksplat::cluster
