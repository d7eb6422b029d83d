#pragma once
// Clusters from neighbour pairs under a semantic constraint: a pair of Gaussians is merged when,
// over the views in which both are visible (region id != kNoRegion), the fraction of views where
// their region ids differ is at most semantic_tol, and there are at least min_common_views such
// views. Merging is transitive (union-find), so a cluster is a connected component of the
// accepted pairs.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "vksplat/cluster/neighbours.hpp"
#include "vksplat/cluster/region_map.hpp"

namespace vksplat::cluster {

// Region ids of every Gaussian in every selected view, view-major: ids[v * gaussians + g].
struct ViewLabels {
    size_t views = 0;
    size_t gaussians = 0;
    std::vector<int32_t> ids;
    int32_t at(size_t view, size_t gaussian) const { return ids[view * gaussians + gaussian]; }
};

struct MergeRule {
    double semantic_tol = 0.1;
    size_t min_common_views = 1;
};

// Disjoint sets over 0..n-1 with path halving and union by size.
class DisjointSets {
public:
    explicit DisjointSets(size_t n);
    uint32_t find(uint32_t x);
    // Returns true when x and y were in different sets.
    bool unite(uint32_t x, uint32_t y);
    size_t size() const { return parent_.size(); }

private:
    std::vector<uint32_t> parent_;
    std::vector<uint32_t> size_;
};

// Per Gaussian, its region ids over the views (gaussian-major), for fast pair checks.
class PairJudge {
public:
    PairJudge(const ViewLabels& labels, const MergeRule& rule);
    bool same_object(uint32_t a, uint32_t b) const;

private:
    std::vector<int32_t> by_gaussian_;
    size_t views_;
    MergeRule rule_;
};

struct ClusterSummary {
    size_t gaussians = 0;
    size_t pairs_considered = 0;
    size_t pairs_merged = 0;
    size_t clusters = 0;
    size_t singletons = 0;
    size_t largest = 0;
    // Cluster size at percentiles 0, 25, 50, 75, 90, 95, 100 (over clusters).
    std::vector<double> size_percentiles;
    // Warnings for degenerate outcomes (all singletons, one cluster holding nearly everything).
    std::vector<std::string> warnings;
};

struct Clustering {
    std::vector<int32_t> cluster_of;  // per Gaussian, ids 0..clusters-1 in order of first member
    ClusterSummary summary;
};

// Streams the neighbour pairs of `positions` through the merge rule.
Clustering build_clusters(std::span<const float> positions, const ViewLabels& labels, const NeighbourParams& neighbours,
                          const MergeRule& rule);
// Numbers the sets of `sets` 0..n-1 and summarises them.
Clustering label_clusters(DisjointSets& sets);

}  // namespace vksplat::cluster
