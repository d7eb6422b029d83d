// Union-find clustering: disjoint sets, the semantic merge rule and the degenerate outcomes.
#include <gtest/gtest.h>

#include "vksplat/cluster/union_find.hpp"

namespace vksplat::cluster {
namespace {

// Labels for two Gaussians over `views` views: a in region 0 everywhere, b in region 0 except in
// `differ` views (region 1) and absent (kNoRegion) in `absent` further views.
ViewLabels two_gaussians(size_t views, size_t differ, size_t absent) {
    ViewLabels labels{views, 2, std::vector<int32_t>(views * 2, 0)};
    for (size_t v = 0; v < differ; ++v) labels.ids[v * 2 + 1] = 1;
    for (size_t v = differ; v < differ + absent; ++v) labels.ids[v * 2 + 1] = kNoRegion;
    return labels;
}

TEST(DisjointSets, UnitesTransitively) {
    DisjointSets sets(5);
    EXPECT_TRUE(sets.unite(0, 1));
    EXPECT_TRUE(sets.unite(3, 4));
    EXPECT_FALSE(sets.unite(1, 0));
    EXPECT_TRUE(sets.unite(1, 4));
    EXPECT_EQ(sets.find(0), sets.find(3));
    EXPECT_NE(sets.find(0), sets.find(2));
    const Clustering c = label_clusters(sets);
    EXPECT_EQ(c.summary.clusters, 2u);
    EXPECT_EQ(c.summary.singletons, 1u);
    EXPECT_EQ(c.summary.largest, 4u);
    EXPECT_EQ(c.cluster_of, (std::vector<int32_t>{0, 0, 1, 0, 0}));  // ids in order of first member
}

TEST(PairJudge, MergesAtMostTheToleratedShareOfDisagreeingViews) {
    const MergeRule rule{0.1, 1};
    EXPECT_TRUE(PairJudge(two_gaussians(10, 0, 0), rule).same_object(0, 1));
    EXPECT_TRUE(PairJudge(two_gaussians(10, 1, 0), rule).same_object(0, 1));   // 1/10 <= 0.1
    EXPECT_FALSE(PairJudge(two_gaussians(10, 2, 0), rule).same_object(0, 1));  // 2/10 > 0.1
    // Views where one of them is not visible do not count: 1 of 5 common views differs.
    EXPECT_FALSE(PairJudge(two_gaussians(10, 1, 5), rule).same_object(0, 1));
    EXPECT_TRUE(PairJudge(two_gaussians(10, 1, 5), {0.2, 1}).same_object(0, 1));
}

TEST(PairJudge, NeedsCommonViews) {
    EXPECT_FALSE(PairJudge(two_gaussians(4, 0, 4), {0.1, 1}).same_object(0, 1));  // never seen together
    EXPECT_TRUE(PairJudge(two_gaussians(4, 0, 2), {0.1, 2}).same_object(0, 1));
    EXPECT_FALSE(PairJudge(two_gaussians(4, 0, 3), {0.1, 2}).same_object(0, 1));
}

// Two rows of Gaussians 0.1 apart along x, the rows 1 apart in y; row 0 in region 0 and row 1 in
// region 1 in every view, except that `mixed` makes every Gaussian's regions differ from its
// neighbours' (noise).
struct Rows {
    std::vector<float> positions;
    ViewLabels labels;
};

Rows two_rows(size_t per_row, size_t views, bool mixed) {
    Rows r;
    const size_t n = per_row * 2;
    r.labels = {views, n, std::vector<int32_t>(views * n)};
    for (size_t g = 0; g < n; ++g) {
        const size_t row = g / per_row;
        r.positions.insert(r.positions.end(), {0.1f * float(g % per_row), float(row), 0.0f});
        for (size_t v = 0; v < views; ++v) r.labels.ids[v * n + g] = mixed ? int32_t((g * 7 + v * 3) % 11) : int32_t(row);
    }
    return r;
}

TEST(BuildClusters, OneClusterPerRegion) {
    const Rows rows = two_rows(20, 6, false);
    const Clustering c = build_clusters(rows.positions, rows.labels, {.delta = 0.15f}, {});
    EXPECT_EQ(c.summary.clusters, 2u);
    EXPECT_EQ(c.summary.singletons, 0u);
    for (size_t g = 0; g < 40; ++g) EXPECT_EQ(c.cluster_of[g], g < 20 ? 0 : 1) << g;
    EXPECT_TRUE(c.summary.warnings.empty());
}

TEST(BuildClusters, TheSemanticConstraintKeepsRegionsApartWhateverDelta) {
    // delta reaches across rows, but the rows' regions differ in every view.
    const Rows rows = two_rows(20, 6, false);
    const Clustering c = build_clusters(rows.positions, rows.labels, {.delta = 5.0f, .max_neighbours = 40}, {});
    EXPECT_EQ(c.summary.clusters, 2u);
}

TEST(BuildClusters, DeltaTooSmallLeavesSingletonsWithAWarning) {
    const Rows rows = two_rows(20, 6, false);
    const Clustering c = build_clusters(rows.positions, rows.labels, {.delta = 0.01f}, {});
    EXPECT_EQ(c.summary.clusters, 40u);
    EXPECT_EQ(c.summary.singletons, 40u);
    ASSERT_EQ(c.summary.warnings.size(), 1u);
    EXPECT_NE(c.summary.warnings[0].find("40 of 40 Gaussians are their own cluster"), std::string::npos);
}

TEST(BuildClusters, DeltaTooLargeGivesOneClusterWithAWarning) {
    Rows rows = two_rows(20, 6, false);
    std::fill(rows.labels.ids.begin(), rows.labels.ids.end(), 0);  // one region everywhere
    const Clustering c = build_clusters(rows.positions, rows.labels, {.delta = 100.0f}, {});
    EXPECT_EQ(c.summary.clusters, 1u);
    ASSERT_EQ(c.summary.warnings.size(), 1u);
    EXPECT_NE(c.summary.warnings[0].find("one cluster holds 40 of 40"), std::string::npos);
}

TEST(BuildClusters, NoiseLabelsMergeNothing) {
    const Rows rows = two_rows(20, 6, true);
    const Clustering c = build_clusters(rows.positions, rows.labels, {.delta = 0.15f}, {});
    EXPECT_EQ(c.summary.singletons, 40u);
    EXPECT_FALSE(c.summary.warnings.empty());
}

TEST(BuildClusters, BatchesDoNotChangeTheResult) {
    const Rows rows = two_rows(50, 4, false);
    const Clustering whole = build_clusters(rows.positions, rows.labels, {.delta = 0.15f}, {});
    const Clustering batched = build_clusters(rows.positions, rows.labels, {.delta = 0.15f, .batch_size = 7}, {});
    EXPECT_EQ(whole.cluster_of, batched.cluster_of);
}

TEST(Neighbours, PairsWithinDeltaCappedPerCentre) {
    const std::vector<float> line{0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0, 10, 0, 0};
    std::vector<Pair> pairs;
    const size_t count = for_each_neighbour_pair(line, {.delta = 1.5f, .max_neighbours = 4},
                                                 [&](std::span<const Pair> batch) { pairs.insert(pairs.end(), batch.begin(), batch.end()); });
    EXPECT_EQ(count, pairs.size());
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    EXPECT_EQ(pairs, (std::vector<Pair>{{0, 1}, {1, 2}, {2, 3}}));  // 10 is alone
    const NearestDistanceStats stats = nearest_distance_stats(line);
    EXPECT_EQ(stats.sampled, 5u);
    EXPECT_DOUBLE_EQ(stats.median, 1.0);
    EXPECT_DOUBLE_EQ(stats.mean, (1 + 1 + 1 + 1 + 7) / 5.0);
    EXPECT_DOUBLE_EQ(auto_delta(stats), 2.0);
}

}  // namespace
}  // namespace vksplat::cluster
