// Cluster scores on hand-made clusters whose variances and visibility are known, and the
// cluster selection.
#include <gtest/gtest.h>

#include "support/scenes.hpp"
#include "vksplat/cluster/cluster_scores.hpp"
#include "vksplat/cluster/region_map.hpp"
#include "vksplat/error.hpp"

namespace vksplat::cluster {
namespace {

// Cluster 0: (+-1, 0, 4), spatial variance 1. Cluster 1: (0, 0, 2|4|6), spatial variance 8/3.
// Cluster 2: a singleton. Two views from a camera at the origin looking down +z (depth = z):
// view 0 sees everything, view 1 sees the first member of cluster 0 and the two nearer members
// of cluster 1.
struct HandMade {
    std::vector<float> positions{-1, 0, 4, 1, 0, 4, 0, 0, 2, 0, 0, 4, 0, 0, 6, 5, 5, 5};
    std::vector<int32_t> cluster_of{0, 0, 1, 1, 1, 2};
    ViewLabels labels{2, 6, {0, 0, 1, 1, 1, 2, /* view 1 */ 0, kNoRegion, 1, 1, kNoRegion, kNoRegion}};
    std::vector<Camera> cameras{test::forward_camera(64, 64, 50), test::forward_camera(64, 64, 50)};
};

TEST(ClusterScores, KnownVariancesAndVisibility) {
    const HandMade m;
    const ClusterScores s = score_clusters(m.positions, m.cluster_of, m.labels, m.cameras, {});
    ASSERT_EQ(s.size(), 3u);
    EXPECT_NEAR(s.spatial_raw[0], 1.0, 1e-9);
    EXPECT_NEAR(s.spatial_raw[1], 8.0 / 3.0, 1e-9);
    EXPECT_NEAR(s.spatial_raw[2], 0.0, 1e-9);
    // Depth: cluster 1 has variance 8/3 in view 0 (z = 2, 4, 6) and 1 in view 1 (z = 2, 4).
    EXPECT_NEAR(s.depth_raw[0], 0.0, 1e-9);
    EXPECT_NEAR(s.depth_raw[1], (8.0 / 3.0 + 1.0) / 2.0, 1e-9);
    EXPECT_NEAR(s.depth_raw[2], 0.0, 1e-9);
    // MVR = 0.7 * coverage + 0.3 * mean visible fraction.
    EXPECT_NEAR(s.mvr[0], 0.7 * 1.0 + 0.3 * (1.0 + 0.5) / 2, 1e-9);
    EXPECT_NEAR(s.mvr[1], 0.7 * 1.0 + 0.3 * (1.0 + 2.0 / 3.0) / 2, 1e-9);
    EXPECT_NEAR(s.mvr[2], 0.7 * 0.5 + 0.3 * (1.0 + 0.0) / 2, 1e-9);
    // Normalised by the 99th percentile (linear interpolation over 3 values: 98% of the way from
    // the second to the largest), clamped to 1.
    const double spatial_p99 = 1.0 + 0.98 * (8.0 / 3.0 - 1.0);
    EXPECT_NEAR(s.spatial[0], 1.0 / spatial_p99, 1e-9);
    EXPECT_EQ(s.spatial[1], 1.0);
    EXPECT_EQ(s.spatial[2], 0.0);
    EXPECT_EQ(s.depth[0], 0.0);
    EXPECT_EQ(s.depth[1], 1.0);
    for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(s.score[c], -0.1 * s.spatial[c] - 0.1 * s.depth[c] + s.mvr[c], 1e-12);
}

TEST(ClusterScores, WeightsChangeTheScore) {
    const HandMade m;
    const ClusterScores s = score_clusters(m.positions, m.cluster_of, m.labels, m.cameras,
                                           {.alpha = 1.0, .beta = 0.0, .gamma = 0.0, .mvr_mean_frac_weight = 1.0});
    EXPECT_NEAR(s.score[1], -1.0, 1e-12);
    EXPECT_NEAR(s.mvr[0], 0.75, 1e-12);  // mean visible fraction alone
}

TEST(ClusterScores, RefusesMismatchedSizes) {
    const HandMade m;
    EXPECT_THROW(score_clusters(m.positions, m.cluster_of, m.labels, {m.cameras[0]}, {}), InputError);
    EXPECT_THROW(score_clusters(std::vector<float>(9), m.cluster_of, m.labels, m.cameras, {}), InputError);
}

TEST(Percentiles, InterpolateLinearly) {
    EXPECT_EQ(percentiles({4, 1, 3, 2}, {0, 50, 100}), (std::vector<double>{1, 2.5, 4}));
    EXPECT_EQ(percentiles({}, {50}), (std::vector<double>{0}));
}

ClusterScores with_scores(std::vector<double> g) {
    ClusterScores s;
    s.score = std::move(g);
    return s;
}

TEST(SelectClusters, DropsTheLowestRatioOfClustersWhole) {
    const std::vector<int32_t> cluster_of{0, 0, 1, 1, 1, 2, 3};
    const ClusterSelection sel = select_clusters(with_scores({0.9, 0.2, 0.5, 0.1}), cluster_of, std::nullopt, 0.5);
    EXPECT_EQ(sel.clusters_dropped, 2u);  // clusters 3 and 1
    EXPECT_EQ(sel.keep, (std::vector<uint8_t>{1, 1, 0, 0, 0, 1, 0}));
    EXPECT_EQ(sel.gaussians_kept, 3u);
    EXPECT_TRUE(sel.warnings.empty());
}

TEST(SelectClusters, ThresholdDropsBelowIt) {
    const std::vector<int32_t> cluster_of{0, 1, 2};
    const ClusterSelection sel = select_clusters(with_scores({0.3, 0.2, 0.1}), cluster_of, 0.2, 0.9);
    EXPECT_EQ(sel.keep, (std::vector<uint8_t>{1, 1, 0}));
}

TEST(SelectClusters, NeverDropsEverythingWithoutSayingSo) {
    const std::vector<int32_t> cluster_of{0, 1, 1};
    const ClusterSelection all = select_clusters(with_scores({0.3, 0.4}), cluster_of, 1.0, 0.9);
    EXPECT_EQ(all.keep, (std::vector<uint8_t>{0, 1, 1}));  // the best cluster stays
    ASSERT_EQ(all.warnings.size(), 1u);
    const ClusterSelection one = select_clusters(with_scores({0.3}), std::vector<int32_t>{0, 0}, std::nullopt, 0.9);
    EXPECT_EQ(one.gaussians_kept, 2u);
    ASSERT_EQ(one.warnings.size(), 1u);
    EXPECT_NE(one.warnings[0].find("drops none"), std::string::npos);
}

TEST(SelectClusters, RefusesABadRatio) {
    EXPECT_THROW(select_clusters(with_scores({0.3}), std::vector<int32_t>{0}, std::nullopt, 1.5), InputError);
}

TEST(GaussianScores, AreTheirClustersScore) {
    EXPECT_EQ(gaussian_scores(with_scores({0.5, -1.0}), std::vector<int32_t>{1, 0, 1}),
              (std::vector<float>{-1.0f, 0.5f, -1.0f}));
}

}  // namespace
}  // namespace vksplat::cluster
