// Union-find clustering under the semantic constraint (see union_find.hpp).
#include "vksplat/cluster/union_find.hpp"

#include <algorithm>
#include <cstdio>

#include "vksplat/cluster/cluster_scores.hpp"
#include "vksplat/cluster/region_map.hpp"
#include "vksplat/error.hpp"

namespace vksplat::cluster {

DisjointSets::DisjointSets(size_t n) : parent_(n), size_(n, 1) {
    for (size_t i = 0; i < n; ++i) parent_[i] = uint32_t(i);
}

uint32_t DisjointSets::find(uint32_t x) {
    while (parent_[x] != x) {
        parent_[x] = parent_[parent_[x]];  // path halving
        x = parent_[x];
    }
    return x;
}

bool DisjointSets::unite(uint32_t x, uint32_t y) {
    x = find(x);
    y = find(y);
    if (x == y) return false;
    if (size_[x] < size_[y]) std::swap(x, y);
    parent_[y] = x;
    size_[x] += size_[y];
    return true;
}

PairJudge::PairJudge(const ViewLabels& labels, const MergeRule& rule)
    : by_gaussian_(labels.views * labels.gaussians), views_(labels.views), rule_(rule) {
    if (labels.ids.size() != labels.views * labels.gaussians)
        throw InputError("view labels", "hold " + std::to_string(labels.ids.size()) + " ids, expected " +
                                            std::to_string(labels.views * labels.gaussians));
    for (size_t v = 0; v < labels.views; ++v)
        for (size_t g = 0; g < labels.gaussians; ++g) by_gaussian_[g * views_ + v] = labels.at(v, g);
}

bool PairJudge::same_object(uint32_t a, uint32_t b) const {
    const int32_t* ra = &by_gaussian_[size_t(a) * views_];
    const int32_t* rb = &by_gaussian_[size_t(b) * views_];
    size_t common = 0, differ = 0;
    for (size_t v = 0; v < views_; ++v) {
        if (ra[v] == kNoRegion || rb[v] == kNoRegion) continue;
        ++common;
        differ += ra[v] != rb[v];
    }
    return common > 0 && common >= rule_.min_common_views && double(differ) <= rule_.semantic_tol * double(common);
}

Clustering label_clusters(DisjointSets& sets) {
    const size_t n = sets.size();
    Clustering result;
    result.cluster_of.assign(n, -1);
    std::vector<int32_t> id_of_root(n, -1);
    std::vector<double> sizes;
    for (size_t i = 0; i < n; ++i) {
        const uint32_t root = sets.find(uint32_t(i));
        if (id_of_root[root] < 0) {
            id_of_root[root] = int32_t(sizes.size());
            sizes.push_back(0);
        }
        result.cluster_of[i] = id_of_root[root];
        sizes[size_t(id_of_root[root])] += 1;
    }
    ClusterSummary& s = result.summary;
    s.gaussians = n;
    s.clusters = sizes.size();
    s.singletons = size_t(std::count(sizes.begin(), sizes.end(), 1.0));
    s.largest = sizes.empty() ? 0 : size_t(*std::max_element(sizes.begin(), sizes.end()));
    s.size_percentiles = percentiles(sizes, kReportPercents);
    if (n > 1 && double(s.singletons) >= 0.9 * double(n))
        s.warnings.push_back(std::to_string(s.singletons) + " of " + std::to_string(n) +
                             " Gaussians are their own cluster: delta is too small for the scene's spacing, or the "
                             "region maps disagree everywhere (noise?); scores then rank single Gaussians");
    else if (n > 1 && double(s.largest) >= 0.9 * double(n))
        s.warnings.push_back("one cluster holds " + std::to_string(s.largest) + " of " + std::to_string(n) +
                             " Gaussians: delta is too large or the region maps do not separate parts, so "
                             "pruning by cluster cannot tell the scene's parts apart");
    return result;
}

Clustering build_clusters(std::span<const float> positions, const ViewLabels& labels, const NeighbourParams& neighbours,
                          const MergeRule& rule) {
    const size_t n = positions.size() / 3;
    if (labels.gaussians != n)
        throw InputError("view labels", "are for " + std::to_string(labels.gaussians) + " Gaussians, the scene has " +
                                            std::to_string(n));
    const PairJudge judge(labels, rule);
    DisjointSets sets(n);
    size_t merged = 0;
    const size_t considered = for_each_neighbour_pair(positions, neighbours, [&](std::span<const Pair> pairs) {
        for (const auto& [a, b] : pairs) {
            if (sets.find(a) == sets.find(b)) continue;
            if (judge.same_object(a, b) && sets.unite(a, b)) ++merged;
        }
    });
    Clustering result = label_clusters(sets);
    result.summary.pairs_considered = considered;
    result.summary.pairs_merged = merged;
    return result;
}

}  // namespace vksplat::cluster
