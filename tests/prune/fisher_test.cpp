// The fisher score: its matrices against finite differences of the reference rasterizer's picture,
// and its order on scenes where the answer is known.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "support/gpu_fixture.hpp"
#include "support/scenes.hpp"
#include "vksplat/prune/accumulate.hpp"
#include "vksplat/prune/fisher.hpp"
#include "vksplat/prune/scores.hpp"
#include "vksplat/reference/rasterizer.hpp"

namespace vksplat::test {
namespace {

using prune::FisherMatrix;

// F by its definition: per Gaussian, central differences (in double, of the reference's
// unrounded colours) of every pixel's channels in each of the 6 parameters, then sum g g^T.
// The parameters are floats, so each step is the float nearest p +- h, and the difference is
// divided by the steps actually taken.
std::vector<FisherMatrix> fisher_by_differences(const GaussianCloud& cloud, const std::vector<Camera>& cameras,
                                                const RenderSettings& settings) {
    constexpr double kStep = 1e-5;
    std::vector<FisherMatrix> fisher(cloud.size(), FisherMatrix{});
    GaussianCloud moved = cloud;
    for (size_t i = 0; i < cloud.size(); ++i) {
        std::array<float*, 6> parameter;
        for (int k = 0; k < 3; ++k) {
            parameter[k] = &moved.positions[i * 3 + k];
            parameter[3 + k] = &moved.log_scales[i * 3 + k];
        }
        for (const Camera& camera : cameras) {
            std::array<std::vector<double>, 6> gradient;
            for (int k = 0; k < 6; ++k) {
                const float original = *parameter[k];
                *parameter[k] = float(original + kStep);
                const double up = double(*parameter[k]) - original;
                const std::vector<double> plus = reference::render_rgb(moved, camera, settings);
                *parameter[k] = float(original - kStep);
                const double down = original - double(*parameter[k]);
                const std::vector<double> minus = reference::render_rgb(moved, camera, settings);
                *parameter[k] = original;
                gradient[k].resize(plus.size());
                for (size_t p = 0; p < plus.size(); ++p) gradient[k][p] = (plus[p] - minus[p]) / (up + down);
            }
            for (int r = 0; r < 6; ++r)
                for (int c = 0; c < 6; ++c)
                    for (size_t p = 0; p < gradient[r].size(); ++p) fisher[i][r * 6 + c] += gradient[r][p] * gradient[c][p];
        }
    }
    return fisher;
}

TEST(Fisher, MatchesFiniteDifferencesOfTheReferencePicture) {
    const auto [cameras, cloud, settings] = fisher_scene();

    prune::FisherInformation information(cloud, settings);
    for (const Camera& camera : cameras) information.add_view(camera);
    const std::vector<FisherMatrix> analytic = information.matrices();
    const std::vector<FisherMatrix> expected = fisher_by_differences(cloud, cameras, settings);

    size_t seen = 0;
    for (size_t i = 0; i < cloud.size(); ++i) {
        SCOPED_TRACE("Gaussian " + std::to_string(i));
        double scale = 0.0;
        for (double v : expected[i]) scale = std::max(scale, std::abs(v));
        seen += scale > 0.0;
        for (int e = 0; e < 36; ++e) EXPECT_NEAR(analytic[i][e], expected[i][e], 1e-5 * scale + 1e-12) << "entry " << e;
        EXPECT_NEAR(prune::fisher_log_det(analytic[i]), prune::fisher_log_det(expected[i]), 1e-2);
    }
    EXPECT_EQ(seen, cloud.size()) << "every Gaussian of the test must show in some view";
}

class FisherScores : public GpuTest {};

TEST_F(FisherScores, HiddenAndUnseenScoreLowestAndAnotherViewAddsToTheSplatInFront) {
    GaussianCloud cloud;
    // Four layers of flat, wide, 0.99-opaque splats stop every pixel before what lies behind.
    for (double z : {2.0, 2.1, 2.2, 2.3}) add_splat(cloud, {.position = {0, 0, z}, .scale = {3, 3, 0.01}, .opacity = 0.99});
    add_splat(cloud, {.position = {0.1, 0, 5}, .scale = glm::dvec3(0.2), .opacity = 0.9});   // hidden
    add_splat(cloud, {.position = {50, 0, 5}, .scale = glm::dvec3(0.2), .opacity = 0.9});    // off screen
    add_splat(cloud, {.position = {0.3, 0.2, 1.5}, .scale = glm::dvec3(0.1), .opacity = 0.6}); // in front
    Renderer renderer(context());
    const std::vector<Camera> cameras = {forward_camera(48, 48, 48.0), forward_camera(40, 56, 60.0)};

    const prune::ViewTotals one = prune::accumulate(renderer, cloud, cameras, {0}, {}, {}, true);
    const prune::ViewTotals both = prune::accumulate(renderer, cloud, cameras, {0, 1}, {}, {}, true);
    EXPECT_TRUE(prune::accumulate(renderer, cloud, cameras, {0}, {}).fisher.empty()) << "gathered only when asked";
    const std::vector<float> scores = prune::score(cloud, both, prune::ScoreMethod::fisher);
    const float floor = float(6.0 * std::log(prune::kFisherEpsilon));
    EXPECT_EQ(scores[4], floor) << "no pixel sees the hidden one";
    EXPECT_EQ(scores[5], floor);
    for (size_t i : {0u, 1u, 6u}) EXPECT_GT(scores[i], floor + 10.0f) << i;
    // Another view adds information to the round splat in front. The flat layers are not compared:
    // seen face-on from both views, their depth direction is near-null and their log det is set by
    // the float sums' rounding (FisherProbes.AnotherViewAddsAPositiveSemiDefiniteShare checks the
    // matrices instead).
    EXPECT_GT(both.fisher[6], one.fisher[6]);
}

}  // namespace
}  // namespace vksplat::test
