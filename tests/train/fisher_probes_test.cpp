// The Fisher estimate by random-sign probes against the exact Fisher information of the CPU
// (prune::FisherInformation, itself checked against finite differences of the reference picture).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <vector>

#include <Eigen/Eigenvalues>

#include "support/gpu_fixture.hpp"
#include "support/scenes.hpp"
#include "vksplat/prune/fisher.hpp"
#include "vksplat/train/fisher_probes.hpp"

namespace vksplat::test {
namespace {

using prune::FisherMatrix;

class FisherProbes : public GpuTest {};

std::vector<FisherMatrix> exact_fisher(const GaussianCloud& cloud, const std::vector<Camera>& cameras,
                                       const RenderSettings& settings) {
    prune::FisherInformation information(cloud, settings);
    for (const Camera& camera : cameras) information.add_view(camera);
    return information.matrices();
}

// Ranks 0 .. n-1 of the values (ties broken by index).
std::vector<double> ranks(const std::vector<double>& values) {
    std::vector<size_t> order(values.size());
    std::iota(order.begin(), order.end(), size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](size_t l, size_t r) { return values[l] < values[r]; });
    std::vector<double> rank(values.size());
    for (size_t k = 0; k < order.size(); ++k) rank[order[k]] = double(k);
    return rank;
}

double spearman(const std::vector<double>& a, const std::vector<double>& b) {
    const std::vector<double> ra = ranks(a), rb = ranks(b);
    const double n = double(a.size());
    double d2 = 0.0;
    for (size_t i = 0; i < a.size(); ++i) d2 += (ra[i] - rb[i]) * (ra[i] - rb[i]);
    return 1.0 - 6.0 * d2 / (n * (n * n - 1.0));
}

TEST_F(FisherProbes, ManyProbesConvergeToTheExactFisherInformation) {
    // The exact Fisher test's scene: a splat clamped at alpha 0.99 and one beyond the Jacobian's clamp.
    const auto [cameras, cloud, settings] = fisher_scene();

    // Each probe's G G^T has mean F and, per entry, a spread of about sqrt(F_rr F_cc + F_rc^2) for
    // one view: 2,048 probes a view bring it to ~2.2% of the diagonal's scale over the two views,
    // and 6 spreads is the bound.
    constexpr uint32_t kProbes = 2048;
    const std::vector<FisherMatrix> exact = exact_fisher(cloud, cameras, settings);
    const auto estimate = train::estimate_fisher(context(), cloud, cameras, settings, {.probes_per_view = kProbes, .seed = 3});
    ASSERT_EQ(estimate.size(), cloud.size());
    size_t seen = 0;
    for (size_t i = 0; i < cloud.size(); ++i) {
        SCOPED_TRACE("Gaussian " + std::to_string(i));
        const auto& f = exact[i];
        if (f[0] + f[7] + f[14] + f[21] + f[28] + f[35] == 0.0) continue;
        ++seen;
        for (int r = 0; r < 6; ++r)
            for (int c = 0; c < 6; ++c) {
                const double spread = std::sqrt((f[r * 6 + r] * f[c * 6 + c] + f[r * 6 + c] * f[r * 6 + c]) / kProbes);
                EXPECT_NEAR(estimate[i][r * 6 + c], f[r * 6 + c], 6.0 * spread + 1e-9) << "entry " << r << ", " << c;
            }
        for (int r = 0; r < 6; ++r)
            for (int c = 0; c < 6; ++c) EXPECT_EQ(estimate[i][r * 6 + c], estimate[i][c * 6 + r]) << "symmetric";
    }
    EXPECT_EQ(seen, cloud.size()) << "every Gaussian of the test must show in some view";
}

TEST_F(FisherProbes, TheDefaultProbesRankGaussiansAsTheExactScoreDoes) {
    // A pruning score is used by its order: with the default 8 probes a view, over five views.
    const std::vector<Camera> cameras = row_of_five_views();
    const GaussianCloud cloud = random_scene(11, 80, 2, 3.0f, 7.0f, 0.03f, 0.3f, 2.0f);
    const RenderSettings settings;
    const std::vector<FisherMatrix> exact = exact_fisher(cloud, cameras, settings);
    const auto estimate = train::estimate_fisher(context(), cloud, cameras, settings);
    std::vector<double> exact_score, estimated_score;
    for (size_t i = 0; i < cloud.size(); ++i) {
        exact_score.push_back(prune::fisher_log_det(exact[i]));
        estimated_score.push_back(prune::fisher_log_det(estimate[i]));
    }
    const double correlation = spearman(exact_score, estimated_score);
    RecordProperty("spearman", std::to_string(correlation));
    EXPECT_GT(correlation, 0.95);
    // Half of them kept by each: the same half but for a few near the cut.
    const std::vector<double> exact_rank = ranks(exact_score), estimated_rank = ranks(estimated_score);
    size_t agree = 0;
    for (size_t i = 0; i < cloud.size(); ++i) agree += (exact_rank[i] >= 40.0) == (estimated_rank[i] >= 40.0);
    EXPECT_GE(agree, cloud.size() * 9 / 10);

    // The seed draws the signs: another seed, another estimate of the same matrices.
    const auto again = train::estimate_fisher(context(), cloud, cameras, settings, {.seed = 1});
    EXPECT_NE(again[0], estimate[0]);
}

// Another view adds its probes' G G^T, a positive semi-definite share: F over views {0, 1} less F
// over view 0 (the same seed, so view 0 draws the same signs) has no eigenvalue below the float
// sums' rounding. Compared as matrices, not as log dets: a splat seen face-on from every view has a
// near-null direction whose eigenvalue, and with it the log det, is set by that rounding.
TEST_F(FisherProbes, AnotherViewAddsAPositiveSemiDefiniteShare) {
    const auto [cameras, cloud, settings] = fisher_scene();
    ASSERT_GE(cameras.size(), 2u);
    const auto one = train::estimate_fisher(context(), cloud, {cameras[0]}, settings);
    const auto both = train::estimate_fisher(context(), cloud, {cameras[0], cameras[1]}, settings);
    size_t grew = 0;
    for (size_t i = 0; i < cloud.size(); ++i) {
        SCOPED_TRACE("Gaussian " + std::to_string(i));
        Eigen::Matrix<double, 6, 6> share;
        double largest = 0.0;
        for (int e = 0; e < 36; ++e) {
            share(e / 6, e % 6) = both[i][e] - one[i][e];
            largest = std::max(largest, std::abs(both[i][e]));
        }
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> solver(share, Eigen::EigenvaluesOnly);
        EXPECT_GE(solver.eigenvalues().minCoeff(), -1e-5 * largest);
        grew += solver.eigenvalues().maxCoeff() > 1e-3 * largest;
    }
    EXPECT_GT(grew, 0u) << "the second view must add to some Gaussian's information";
}

TEST_F(FisherProbes, RefusesNoProbesAndAnUnsanitisedCloud) {
    GaussianCloud cloud = random_scene(5, 4, 0);
    const std::vector<Camera> cameras = {forward_camera(32, 32, 32.0)};
    EXPECT_THROW(train::estimate_fisher(context(), cloud, cameras, {}, {.probes_per_view = 0}), std::invalid_argument);
    cloud.rotations[0] = cloud.rotations[1] = cloud.rotations[2] = cloud.rotations[3] = 0.0f;
    EXPECT_THROW(train::estimate_fisher(context(), cloud, cameras, {}), std::invalid_argument);
    EXPECT_TRUE(train::estimate_fisher(context(), GaussianCloud{}, cameras, {}).empty());
}

}  // namespace
}  // namespace vksplat::test
