// The named cluster settings (jobs::ClusterPreset): what each sets, what it leaves, and the names.
#include <gtest/gtest.h>

#include "io/io_test_helpers.hpp"
#include "vksplat/jobs/cluster_prune.hpp"

namespace vksplat::test {
namespace {

TEST(ClusterPreset, SetsTheScoreAndTheSelectionAndLeavesTheOtherStages) {
    jobs::ClusterOptions options;
    options.max_views = 7;
    options.weights.alpha = 0.3;
    options.selection.threshold = 0.5;
    jobs::apply_cluster_preset(jobs::ClusterPreset::keep_subject, options);
    EXPECT_EQ(options.max_views, 7u);
    EXPECT_EQ(options.weights.lambda, 1.0);
    EXPECT_EQ(options.weights.kappa, 1.0);
    EXPECT_EQ(options.weights.alpha, 0.0);  // the preset's whole score, not a mix with what was set
    EXPECT_FALSE(options.selection.threshold.has_value());
    EXPECT_EQ(options.selection.ratio, 0.8);
    EXPECT_EQ(options.selection.ratio_of, cluster::RatioOf::gaussians);
    EXPECT_EQ(options.selection.max_contribution_loss, 1.0);

    jobs::apply_cluster_preset(jobs::ClusterPreset::original, options);
    EXPECT_EQ(options.weights.gamma, cluster::kOriginalWeights.gamma);
    EXPECT_EQ(options.weights.kappa, 0.0);
    EXPECT_EQ(options.weights.lambda, 0.0);
    EXPECT_EQ(options.selection.ratio, 0.9);
    EXPECT_EQ(options.selection.ratio_of, cluster::RatioOf::clusters);

    jobs::apply_cluster_preset(jobs::ClusterPreset::whole_picture, options);
    const jobs::ClusterOptions defaults;
    EXPECT_EQ(options.weights.kappa, defaults.weights.kappa);
    EXPECT_EQ(options.weights.lambda, defaults.weights.lambda);
    EXPECT_EQ(options.selection.ratio, defaults.selection.ratio);
    EXPECT_EQ(options.selection.max_contribution_loss, defaults.selection.max_contribution_loss);
}

TEST(ClusterPreset, NamesRoundTripAndAnUnknownOneIsRefused) {
    for (auto preset : {jobs::ClusterPreset::whole_picture, jobs::ClusterPreset::keep_subject, jobs::ClusterPreset::original})
        EXPECT_EQ(jobs::parse_cluster_preset(jobs::to_string(preset)), preset);
    io::test::expect_input_error([] { jobs::parse_cluster_preset("subject"); }, {"--preset subject", "keep-subject"});
}

}  // namespace
}  // namespace vksplat::test
