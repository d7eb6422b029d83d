// Importance scores on scenes and totals where the right answer is known.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/gpu_fixture.hpp"
#include "support/scenes.hpp"
#include "vksplat/error.hpp"
#include "vksplat/prune/accumulate.hpp"
#include "vksplat/prune/scores.hpp"
#include "vksplat/prune/selection.hpp"

namespace vksplat::test {
namespace {

using prune::ScoreMethod;

class Scores : public GpuTest {};

TEST(ScoreNames, RoundTripAndRefuseUnknownNames) {
    const std::vector<std::string> names = prune::score_method_names();
    ASSERT_EQ(names, (std::vector<std::string>{"opacity", "footprint", "blend", "blend-max", "blend-mix",
                                               "volume-blend", "random", "fisher"}));
    for (const auto& name : names) EXPECT_EQ(prune::to_string(prune::parse_score_method(name)), name);
    try {
        prune::parse_score_method("blend_max");
        FAIL() << "an unknown name was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("'blend_max': unknown (use one of opacity, footprint"), std::string::npos)
            << e.what();
    }
    EXPECT_FALSE(prune::uses_views(ScoreMethod::opacity));
    EXPECT_FALSE(prune::uses_views(ScoreMethod::random));
    EXPECT_TRUE(prune::uses_views(ScoreMethod::blend_max));
    EXPECT_TRUE(prune::uses_views(ScoreMethod::fisher));
    EXPECT_TRUE(prune::needs_fisher(ScoreMethod::fisher));
    EXPECT_FALSE(prune::needs_fisher(ScoreMethod::blend));
}

TEST(ScoreValues, OpacityIsTheSigmoidOfTheLogit) {
    GaussianCloud cloud;
    cloud.resize(3);
    cloud.opacity_logits = {0.0f, 2.0f, -30.0f};
    const auto scores = prune::score(cloud, {}, ScoreMethod::opacity);
    EXPECT_FLOAT_EQ(scores[0], 0.5f);
    EXPECT_FLOAT_EQ(scores[1], float(1.0 / (1.0 + std::exp(-2.0))));
    EXPECT_GT(scores[2], 0.0f);
    EXPECT_LT(scores[2], 1e-12f);
}

TEST(ScoreValues, ViewScoresReadTheTotals) {
    GaussianCloud cloud;
    cloud.resize(2);
    prune::ViewTotals totals(2);
    totals.blend = {3.5, 0.25};
    totals.blend_max = {0.75f, 0.5f};
    totals.footprint = {100.0, 7.0};
    EXPECT_EQ(prune::score(cloud, totals, ScoreMethod::blend), (std::vector<float>{3.5f, 0.25f}));
    EXPECT_EQ(prune::score(cloud, totals, ScoreMethod::blend_max), (std::vector<float>{0.75f, 0.5f}));
    EXPECT_EQ(prune::score(cloud, totals, ScoreMethod::footprint), (std::vector<float>{100.0f, 7.0f}));
    const auto mix = prune::score(cloud, totals, ScoreMethod::blend_mix);
    ASSERT_EQ(mix.size(), 2u);
    EXPECT_FLOAT_EQ(mix[0], float(std::sqrt(3.5 * 0.75)));
    EXPECT_FLOAT_EQ(mix[1], float(std::sqrt(0.25 * 0.5)));
    EXPECT_THROW(prune::score(cloud, prune::ViewTotals(3), ScoreMethod::blend), std::invalid_argument);
    EXPECT_NO_THROW(prune::score(cloud, prune::ViewTotals(3), ScoreMethod::opacity)) << "opacity reads no totals";
    EXPECT_THROW(prune::score(cloud, totals, ScoreMethod::fisher), InputError) << "totals gathered without fisher";
    totals.fisher = {-3.0f, 12.5f};
    EXPECT_EQ(prune::score(cloud, totals, ScoreMethod::fisher), (std::vector<float>{-3.0f, 12.5f}));
}

TEST(ScoreValues, PercentileInterpolatesAsNumPyDoes) {
    // np.percentile([4, 1, 3, 2, 10], 90) = 7.6; np.percentile([5], 90) = 5.
    EXPECT_DOUBLE_EQ(prune::percentile({4, 1, 3, 2, 10}, 90.0), 7.6);
    EXPECT_DOUBLE_EQ(prune::percentile({4, 1, 3, 2, 10}, 50.0), 3.0);
    EXPECT_DOUBLE_EQ(prune::percentile({4, 1, 3, 2, 10}, 100.0), 10.0);
    EXPECT_DOUBLE_EQ(prune::percentile({5}, 90.0), 5.0);
    EXPECT_DOUBLE_EQ(prune::percentile({}, 90.0), 0.0);
}

TEST(ScoreValues, VolumeBlendIsBlendTimesTheNormalisedVolumeToThePowerOfATenth) {
    GaussianCloud cloud;
    cloud.resize(11);
    prune::ViewTotals totals(11);
    std::vector<double> volume(11);
    for (size_t i = 0; i < 11; ++i) {
        // Scales 0.1 * (i + 1) on x, 0.5 on y, 2 on z: volumes 0.1 (i + 1), V90 = 1.0 (index 9 of 0..10).
        cloud.log_scales[3 * i] = std::log(0.1f * float(i + 1));
        cloud.log_scales[3 * i + 1] = std::log(0.5f);
        cloud.log_scales[3 * i + 2] = std::log(2.0f);
        volume[i] = 0.1 * double(i + 1);
        totals.blend[i] = 10.0 - double(i);
    }
    ASSERT_NEAR(prune::percentile(volume, 90.0), 1.0, 1e-12);
    const auto scores = prune::score(cloud, totals, ScoreMethod::volume_blend);
    for (size_t i = 0; i < 11; ++i)
        EXPECT_NEAR(scores[i], totals.blend[i] * std::pow(volume[i] / 1.0, 0.1), 1e-5) << i;
    EXPECT_NEAR(scores[9], totals.blend[9], 1e-5) << "the 90th-percentile volume leaves blend as it is";
}

TEST(ScoreValues, RandomIsDeterministicPortableAndSeeded) {
    GaussianCloud cloud;
    cloud.resize(1000);
    const auto a = prune::score(cloud, {}, ScoreMethod::random, 0);
    EXPECT_EQ(a, prune::score(cloud, {}, ScoreMethod::random, 0));
    const auto b = prune::score(cloud, {}, ScoreMethod::random, 42);
    EXPECT_NE(a, b);
    // std::mt19937_64's output is fixed by the standard, so these hold on every platform.
    EXPECT_EQ(a[0], 2680887.0f / 16777216.0f);
    EXPECT_EQ(a[1], 16645434.0f / 16777216.0f);
    EXPECT_EQ(b[0], 12669407.0f / 16777216.0f);
    for (float s : a) {
        EXPECT_GE(s, 0.0f);
        EXPECT_LT(s, 1.0f);
    }
}

TEST(ScoreValues, SamplingWeighsFisherByTheSixthRootOfItsDeterminant) {
    // log det F of -120 (a Gaussian no pixel pins down), -6, 0 and 12: weights det^(1/6) / largest.
    const std::vector<float> fisher = {-120.0f, -6.0f, 0.0f, 12.0f};
    const std::vector<float> weights = prune::sampling_weights(fisher, prune::ScoreMethod::fisher);
    ASSERT_EQ(weights.size(), 4u);
    EXPECT_FLOAT_EQ(weights[3], 1.0f);
    EXPECT_FLOAT_EQ(weights[2], float(std::exp(-2.0)));
    EXPECT_FLOAT_EQ(weights[1], float(std::exp(-3.0)));
    EXPECT_GT(weights[0], 0.0f) << "still drawn, rarely";
    EXPECT_LT(weights[0], 1e-9f);
    // The sums of contributions are weights as they are.
    const std::vector<float> blend = {0.0f, 2.5f, 7.0f};
    EXPECT_EQ(prune::sampling_weights(blend, prune::ScoreMethod::blend_mix), blend);
    EXPECT_TRUE(prune::sampling_weights({}, prune::ScoreMethod::fisher).empty());
}

TEST_F(Scores, HiddenBehindAnOpaqueWallScoresZeroAndOffScreenIsDroppedLosslessly) {
    GaussianCloud cloud;
    // Four layers of flat, wide, 0.99-opaque splats stop every pixel before what lies behind.
    for (double z : {2.0, 2.1, 2.2, 2.3}) add_splat(cloud, {.position = {0, 0, z}, .scale = {3, 3, 0.01}, .opacity = 0.99});
    add_splat(cloud, {.position = {0.1, 0, 5}, .scale = glm::dvec3(0.2), .opacity = 0.9});  // hidden
    add_splat(cloud, {.position = {50, 0, 5}, .scale = glm::dvec3(0.2), .opacity = 0.9});   // off screen

    Renderer renderer(context());
    const std::vector<Camera> cameras = {forward_camera(48, 48, 48.0), forward_camera(40, 56, 60.0)};
    const prune::ViewTotals totals = prune::accumulate(renderer, cloud, cameras, {0, 1}, {});
    EXPECT_EQ(totals.views, 2u);
    const auto blend = prune::score(cloud, totals, ScoreMethod::blend);
    const auto blend_max = prune::score(cloud, totals, ScoreMethod::blend_max);
    EXPECT_GT(blend[0], 100.0f);
    EXPECT_EQ(totals.views_visible[4], 2u) << "the hidden one is in view, only covered";
    EXPECT_EQ(blend[4], 0.0f);
    EXPECT_EQ(blend_max[4], 0.0f);
    EXPECT_GT(totals.footprint[4], 0.0) << "footprint does not see occlusion";
    EXPECT_EQ(totals.views_visible[5], 0u);
    EXPECT_EQ(totals.footprint[5], 0.0);

    const prune::KeepMask lossless = prune::lossless_mask(totals);
    EXPECT_EQ(lossless, (prune::KeepMask{1, 1, 1, 1, 0, 0}));
    // Every method drops them first, even one that ranks them high.
    const auto opacity = prune::score(cloud, totals, ScoreMethod::opacity);
    EXPECT_EQ(prune::select_count(opacity, 6, lossless), lossless);
}

TEST_F(Scores, FootprintOfAKnownRadius) {
    // An isotropic Gaussian of sigma 0.1 on the axis at depth 4, focal 100: sigma 2.5 px, variance
    // 6.25 + 0.3 (low-pass) = 6.55, radius ceil(3 sqrt(6.55)) = ceil(7.68) = 8 px.
    GaussianCloud cloud;
    add_splat(cloud, {.position = {0, 0, 4}, .scale = glm::dvec3(0.1), .opacity = 0.6});
    add_splat(cloud, {.position = {0, 0, -4}, .scale = glm::dvec3(0.1), .opacity = 0.6});  // behind the camera

    Renderer renderer(context());
    const std::vector<Camera> cameras = {forward_camera(64, 64, 100.0)};
    const prune::ViewTotals totals = prune::accumulate(renderer, cloud, cameras, {0, 0, 0}, {});
    const auto footprint = prune::score(cloud, totals, ScoreMethod::footprint);
    EXPECT_NEAR(footprint[0], 3 * 0.6 * std::numbers::pi * 64.0, 1e-3);
    EXPECT_EQ(totals.views_visible[0], 3u);
    EXPECT_EQ(footprint[1], 0.0f);
}

}  // namespace
}  // namespace vksplat::test
