// The named cluster settings (jobs::ClusterPreset): what each sets, what it leaves, the names, and
// the automatic choice between keep-subject and whole-picture.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "io/io_test_helpers.hpp"
#include "support/scenes.hpp"
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

// A subject of `subject` splats in the ball of radius 0.5 at the origin, where the cameras of
// camera_ring look, and `room` splats on the sphere of radius 10 around it: walls, floor and
// ceiling beyond the ring, each near the middle of a few pictures at most.
GaussianCloud subject_in_room(size_t subject, size_t room) {
    GaussianCloud cloud;
    cloud.sh_degree = 0;
    std::mt19937 random(11);
    std::normal_distribution<double> normal;
    std::uniform_real_distribution<double> uniform;
    const auto direction = [&] {
        const glm::dvec3 d{normal(random), normal(random), normal(random)};
        return d / glm::length(d);
    };
    for (size_t i = 0; i < subject; ++i) add_splat(cloud, {.position = 0.5 * std::cbrt(uniform(random)) * direction()});
    for (size_t i = 0; i < room; ++i) add_splat(cloud, {.position = 10.0 * direction(), .scale = {0.5, 0.5, 0.5}});
    return cloud;
}

const std::vector<Camera> kRing = camera_ring(12, {0, 0, 0}, 4.0);

TEST(AutomaticClusterPreset, KeepsTheSubjectWhereMostOfTheSceneIsARoomTheViewsDoNotLookAt) {
    const auto choice = jobs::choose_cluster_preset(subject_in_room(200, 600), kRing, {});
    EXPECT_EQ(choice.preset, jobs::ClusterPreset::keep_subject);
    EXPECT_EQ(choice.gaussians, 800u);
    EXPECT_EQ(choice.room, 600u);  // every room splat, no subject splat
    EXPECT_EQ(choice.views, kRing.size());
    EXPECT_DOUBLE_EQ(choice.room_share(), 0.75);
}

TEST(AutomaticClusterPreset, KeepsTheWholePictureOfAnObjectOrOfASceneLessThanHalfRoom) {
    const auto object = jobs::choose_cluster_preset(subject_in_room(800, 0), kRing, {});
    EXPECT_EQ(object.preset, jobs::ClusterPreset::whole_picture);
    EXPECT_EQ(object.room, 0u);
    // Some room, as in snowmiku (39%): keep-subject's 80% would take much of the subject too.
    const auto some_room = jobs::choose_cluster_preset(subject_in_room(500, 300), kRing, {});
    EXPECT_EQ(some_room.preset, jobs::ClusterPreset::whole_picture);
    EXPECT_EQ(some_room.room, 300u);
    const auto half_room = jobs::choose_cluster_preset(subject_in_room(400, 400), kRing, {});
    EXPECT_EQ(half_room.preset, jobs::ClusterPreset::keep_subject);
}

TEST(AutomaticClusterPreset, MeasuresInTheRenderedViewsAtTheScoresThreshold) {
    const GaussianCloud cloud = subject_in_room(200, 600);
    jobs::ClusterOptions options;
    options.max_views = 5;
    options.weights.central_threshold = 0.0;  // nothing is under it: no room
    const auto choice = jobs::choose_cluster_preset(cloud, kRing, options);
    EXPECT_EQ(choice.views, 5u);
    EXPECT_EQ(choice.central_threshold, 0.0);
    EXPECT_EQ(choice.room, 0u);
    EXPECT_EQ(choice.preset, jobs::ClusterPreset::whole_picture);
}

TEST(AutomaticClusterPreset, SaysWhatItChoseAndWhy) {
    const std::string line = jobs::describe(jobs::choose_cluster_preset(subject_in_room(200, 600), kRing, {}));
    EXPECT_NE(line.find("preset: keep-subject"), std::string::npos) << line;
    EXPECT_NE(line.find("75.0% of the 800 Gaussians"), std::string::npos) << line;
    EXPECT_NE(line.find("under 0.25 in the 12 views"), std::string::npos) << line;
    EXPECT_NE(line.find("keep-subject from 50%"), std::string::npos) << line;
}

}  // namespace
}  // namespace vksplat::test
