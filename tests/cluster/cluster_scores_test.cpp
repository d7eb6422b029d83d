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

ClusterScores with_scores(std::vector<double> g) {
    ClusterScores s;
    s.score = std::move(g);
    return s;
}

constexpr ScoreWeights kOriginal = kOriginalWeights;  // the G*

TEST(ClusterScores, KnownVariancesAndVisibility) {
    const HandMade m;
    const ClusterScores s = score_clusters(m.positions, m.cluster_of, m.labels, m.cameras, kOriginal);
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
                                           {.alpha = 1.0, .beta = 0.0, .gamma = 0.0, .mvr_mean_frac_weight = 1.0,
                                            .kappa = 0.0});
    EXPECT_NEAR(s.score[1], -1.0, 1e-12);
    EXPECT_NEAR(s.mvr[0], 0.75, 1e-12);  // mean visible fraction alone
}

TEST(ClusterScores, RefusesMismatchedSizes) {
    const HandMade m;
    EXPECT_THROW(score_clusters(m.positions, m.cluster_of, m.labels, {m.cameras[0]}, kOriginal), InputError);
    EXPECT_THROW(score_clusters(std::vector<float>(9), m.cluster_of, m.labels, m.cameras, kOriginal), InputError);
    // The default G* reads contributions: none, or the wrong number, is refused.
    EXPECT_THROW(score_clusters(m.positions, m.cluster_of, m.labels, m.cameras, {}), InputError);
    EXPECT_THROW(score_clusters(m.positions, m.cluster_of, m.labels, m.cameras, {}, std::vector<float>(5, 0.1f)),
                 InputError);
}

// The contribution term on clusters whose answer is known. Cluster 0: a singleton that paints
// 30% of the picture (a large splat filling a surface), seen by view 0 alone, so its MVR is low.
// Cluster 1: three Gaussians that every view's labels reach, but hidden behind others: they paint
// nothing. Cluster 2: two Gaussians off-screen in both views. Cluster 3: four Gaussians each
// painting 1%, seen by both views.
struct WithContribution {
    std::vector<float> positions{0, 0, 4, /* 1 */ 1, 0, 5, 1, 0.1f, 5, 1, 0.2f, 5, /* 2 */ 50, 0, 4, 50, 1, 4,
                                 /* 3 */ -1, 0, 4, -1, 0.1f, 4, -1, 0.2f, 4, -1, 0.3f, 4};
    std::vector<int32_t> cluster_of{0, 1, 1, 1, 2, 2, 3, 3, 3, 3};
    ViewLabels labels{2, 10, {0, 1, 1, 1, kNoRegion, kNoRegion, 2, 2, 2, 2,
                              /* view 1 */ kNoRegion, 1, 1, 1, kNoRegion, kNoRegion, 2, 2, 2, 2}};
    std::vector<Camera> cameras{test::forward_camera(64, 64, 50), test::forward_camera(64, 64, 50)};
    std::vector<float> contribution{0.3f, 0, 0, 0, 0, 0, 0.01f, 0.01f, 0.01f, 0.01f};
};

TEST(ClusterScores, ContributionKeepsAPaintingSingletonAndDropsHiddenAndOffScreenClusters) {
    const WithContribution m;
    const ClusterScores s = score_clusters(m.positions, m.cluster_of, m.labels, m.cameras, {}, m.contribution);
    ASSERT_EQ(s.size(), 4u);
    EXPECT_EQ(s.members, (std::vector<size_t>{1, 3, 2, 4}));
    EXPECT_NEAR(s.contribution_raw[0], 0.3, 1e-7);
    EXPECT_EQ(s.contribution_raw[1], 0.0);
    EXPECT_EQ(s.contribution_raw[2], 0.0);
    EXPECT_NEAR(s.contribution_raw[3], 0.04, 1e-7);
    // The largest member's, normalised by the 99th percentile of (0.3, 0, 0, 0.01): the singleton is at 1.
    EXPECT_EQ(s.contribution[0], 1.0);
    EXPECT_EQ(s.contribution[1], 0.0);
    const double p99 = 0.01 + 0.97 * (0.3 - 0.01);
    EXPECT_NEAR(s.contribution[3], 0.01 / p99, 1e-6);
    // Every cluster but the off-screen pair lies well inside both pictures: central.
    EXPECT_EQ(s.centrality[2], 0.0);
    for (size_t c : {0, 1, 3}) EXPECT_GT(s.centrality[c], 0.8) << c;
    for (size_t c = 0; c < 4; ++c) EXPECT_EQ(s.score[c], s.contribution[c]) << "the default G* is contribution alone";
    const ClusterScores central = score_clusters(m.positions, m.cluster_of, m.labels, m.cameras, {.lambda = 1.0},
                                                 m.contribution);
    for (size_t c = 0; c < 4; ++c)
        EXPECT_EQ(central.score[c], s.contribution[c] + (c == 2 ? 0.0 : 1.0)) << "lambda 1: +1 where central";
    const ClusterScores both = score_clusters(m.positions, m.cluster_of, m.labels, m.cameras,
                                              {.alpha = 0.1, .beta = 0.1, .gamma = 1.0, .kappa = 2.0}, m.contribution);
    for (size_t c = 0; c < 4; ++c)
        EXPECT_NEAR(both.score[c], -0.1 * both.spatial[c] - 0.1 * both.depth[c] + both.mvr[c] + 2 * both.contribution[c],
                    1e-12);

    // Half the Gaussians (5 of 10) go: the off-screen pair and the hidden three, never the singleton.
    const ClusterSelection half = select_clusters(s, m.cluster_of, {.ratio = 0.5});
    EXPECT_EQ(half.keep, (std::vector<uint8_t>{1, 0, 0, 0, 0, 0, 1, 1, 1, 1}));
    EXPECT_EQ(half.contribution_dropped, 0.0);
    EXPECT_FALSE(half.stopped_by_contribution);

    // A cluster is worth its largest member: one painting splat among faint ones keeps it.
    std::vector<float> one_painter = m.contribution;
    one_painter[7] = 0.2f;
    const ClusterScores painted = score_clusters(m.positions, m.cluster_of, m.labels, m.cameras, {}, one_painter);
    EXPECT_GT(painted.score[3], s.score[3]);

    // The original G* ranks the hidden cluster (seen by both views' labels) above the singleton
    // (seen by one) and drops the singleton first.
    const ClusterScores original = score_clusters(m.positions, m.cluster_of, m.labels, m.cameras, kOriginal);
    EXPECT_LT(original.score[0], original.score[1]);
    const ClusterSelection two = select_clusters(original, m.cluster_of, {.ratio = 0.5, .ratio_of = RatioOf::clusters});
    EXPECT_EQ(two.keep[0], 0);
    EXPECT_EQ(two.keep[1], 1);
}

TEST(SelectClusters, TheContributionLimitStopsBeforeTheRatio) {
    const WithContribution m;
    const ClusterScores s = score_clusters(m.positions, m.cluster_of, m.labels, m.cameras, {}, m.contribution);
    // All but the best cluster would go at ratio 0.9; cluster 3 paints 0.04 / 0.34 of the picture.
    const ClusterSelection capped = select_clusters(s, m.cluster_of, {.ratio = 0.9, .max_contribution_loss = 0.1});
    EXPECT_EQ(capped.keep, (std::vector<uint8_t>{1, 0, 0, 0, 0, 0, 1, 1, 1, 1}));
    EXPECT_TRUE(capped.stopped_by_contribution);
    const ClusterSelection loose = select_clusters(s, m.cluster_of, {.ratio = 0.9, .max_contribution_loss = 0.2});
    EXPECT_EQ(loose.gaussians_kept, 1u);
    EXPECT_NEAR(loose.contribution_dropped, 0.04 / 0.34, 1e-6);
    EXPECT_THROW(select_clusters(s, m.cluster_of, {.max_contribution_loss = 1.5}), InputError);
    // A limit needs the contributions.
    ClusterScores bare;
    bare.score = s.score;
    EXPECT_THROW(select_clusters(bare, m.cluster_of, {.max_contribution_loss = 0.1}), InputError);
}

TEST(SelectClusters, ARatioOfGaussiansTakesWholeClustersUntilItIsReached) {
    const std::vector<int32_t> cluster_of{0, 0, 1, 1, 1, 2, 3};
    // Order, worst first: 3 (1 member), 1 (3), 2, 0. Ratio 0.3 of 7 = 2 Gaussians: clusters 3 and 1 (4).
    const ClusterSelection sel = select_clusters(with_scores({0.9, 0.2, 0.5, 0.1}), cluster_of, {.ratio = 0.3});
    EXPECT_EQ(sel.keep, (std::vector<uint8_t>{1, 1, 0, 0, 0, 1, 0}));
    EXPECT_EQ(sel.clusters_dropped, 2u);
    EXPECT_EQ(select_clusters(with_scores({0.9, 0.2, 0.5, 0.1}), cluster_of, {.ratio = 0.1}).gaussians_kept, 6u);
    EXPECT_EQ(parse_ratio_of("clusters"), RatioOf::clusters);
    EXPECT_EQ(to_string(RatioOf::gaussians), "gaussians");
    EXPECT_THROW(parse_ratio_of("splats"), InputError);
}

TEST(Percentiles, InterpolateLinearly) {
    EXPECT_EQ(percentiles({4, 1, 3, 2}, {0, 50, 100}), (std::vector<double>{1, 2.5, 4}));
    EXPECT_EQ(percentiles({}, {50}), (std::vector<double>{0}));
}

TEST(SelectClusters, DropsTheLowestRatioOfClustersWhole) {
    const std::vector<int32_t> cluster_of{0, 0, 1, 1, 1, 2, 3};
    const ClusterSelection sel = select_clusters(with_scores({0.9, 0.2, 0.5, 0.1}), cluster_of, {.ratio = 0.5, .ratio_of = RatioOf::clusters});
    EXPECT_EQ(sel.clusters_dropped, 2u);  // clusters 3 and 1
    EXPECT_EQ(sel.keep, (std::vector<uint8_t>{1, 1, 0, 0, 0, 1, 0}));
    EXPECT_EQ(sel.gaussians_kept, 3u);
    EXPECT_TRUE(sel.warnings.empty());
}

TEST(SelectClusters, ThresholdDropsBelowIt) {
    const std::vector<int32_t> cluster_of{0, 1, 2};
    const ClusterSelection sel = select_clusters(with_scores({0.3, 0.2, 0.1}), cluster_of, {.threshold = 0.2, .ratio = 0.9});
    EXPECT_EQ(sel.keep, (std::vector<uint8_t>{1, 1, 0}));
}

TEST(SelectClusters, NeverDropsEverythingWithoutSayingSo) {
    const std::vector<int32_t> cluster_of{0, 1, 1};
    const ClusterSelection all = select_clusters(with_scores({0.3, 0.4}), cluster_of, {.threshold = 1.0, .ratio = 0.9});
    EXPECT_EQ(all.keep, (std::vector<uint8_t>{0, 1, 1}));  // the best cluster stays
    ASSERT_EQ(all.warnings.size(), 1u);
    const ClusterSelection one = select_clusters(with_scores({0.3}), std::vector<int32_t>{0, 0}, {.ratio = 0.9, .ratio_of = RatioOf::clusters});
    EXPECT_EQ(one.gaussians_kept, 2u);
    ASSERT_EQ(one.warnings.size(), 1u);
    EXPECT_NE(one.warnings[0].find("drops none"), std::string::npos);
}

TEST(SelectClusters, RefusesABadRatio) {
    EXPECT_THROW(select_clusters(with_scores({0.3}), std::vector<int32_t>{0}, {.ratio = 1.5}), InputError);
}

TEST(GaussianScores, AreTheirClustersScore) {
    EXPECT_EQ(gaussian_scores(with_scores({0.5, -1.0}), std::vector<int32_t>{1, 0, 1}),
              (std::vector<float>{-1.0f, 0.5f, -1.0f}));
}

}  // namespace
}  // namespace vksplat::cluster
