// The quality budget: a bisection that finds a count, probes that respect it, and SH reduction.
#include <gtest/gtest.h>

#include <cmath>

#include "support/gpu_fixture.hpp"
#include "support/scenes.hpp"
#include "vksplat/error.hpp"
#include "vksplat/prune/quality_budget.hpp"
#include "vksplat/prune/scores.hpp"

namespace vksplat::test {
namespace {

class QualityBudget : public GpuTest {
protected:
    std::vector<Camera> cameras() const {
        return {forward_camera(64, 48, 60.0),
                Camera::look_at({1.0, -0.5, 0.0}, {0.0, 0.0, 5.0}, {0.0, -1.0, 0.0}, 48, 48, 50.0, 50.0)};
    }
};

// Every probe at the scene's own degree agrees with a bisection that ends at the count found: each
// lies inside the interval left by those before it, and the count below the answer missed.
void expect_bisection(const prune::BudgetResult& result, size_t candidates, int sh_degree) {
    ASSERT_FALSE(result.probes.empty());
    EXPECT_EQ(result.probes.front().kept, candidates);
    EXPECT_TRUE(result.probes.front().meets);
    size_t low = 0, high = candidates;
    size_t probes = 0;
    for (size_t p = 1; p < result.probes.size(); ++p) {
        const prune::BudgetProbe& probe = result.probes[p];
        if (probe.sh_degree != sh_degree) continue;
        ++probes;
        EXPECT_GE(probe.kept, low) << "probe " << p;
        EXPECT_LT(probe.kept, high) << "probe " << p;
        if (probe.meets)
            high = probe.kept;
        else
            low = probe.kept + 1;
        EXPECT_EQ(probe.meets, probe.kept >= result.kept) << "probe " << p;
    }
    EXPECT_EQ(low, high);
    EXPECT_EQ(high, result.kept);
    EXPECT_LE(double(probes), std::ceil(std::log2(double(candidates) + 1)));
    if (result.kept > 0) {
        bool below_missed = false;
        for (const auto& probe : result.probes) below_missed |= probe.kept == result.kept - 1 && !probe.meets;
        EXPECT_TRUE(below_missed);
    }
}

TEST_F(QualityBudget, AgainstTheUnprunedRenderFindsACountByBisection) {
    const GaussianCloud cloud = random_scene(61, 800, 1);
    Renderer renderer(context());
    const eval::TestViews views = eval::render_targets(renderer, cloud, cameras(), {});
    EXPECT_FALSE(views.photos);
    const auto scores = prune::score(cloud, {}, prune::ScoreMethod::opacity);
    const prune::Ranking ranking(scores, prune::keep_all(cloud.size()));

    prune::QualityBudget budget;
    budget.max_psnr_drop = 0.5;
    size_t heard = 0;
    const prune::BudgetResult result = prune::fit_quality_budget(renderer, cloud, ranking, views, budget, {},
                                                                 [&](const prune::BudgetProbe&) { ++heard; });
    EXPECT_EQ(heard, result.probes.size());
    EXPECT_TRUE(result.met);
    EXPECT_EQ(result.baseline_psnr, 0.0);
    EXPECT_EQ(result.sh_degree, 1);
    EXPECT_GT(result.kept, 10u);
    EXPECT_LT(result.kept, 700u) << "half a dB must allow dropping the faintest";
    EXPECT_LE(result.drop, 0.5);
    EXPECT_EQ(prune::count_kept(result.keep), result.kept);
    EXPECT_EQ(result.probes.front().drop, 0.0) << "the whole scene is its own target";
    expect_bisection(result, cloud.size(), 1);

    // The drop is the estimate quality_budget.hpp defines, from the PSNR against the unpruned render.
    const eval::Quality q = eval::measure_quality(renderer, cloud.subset(result.keep), views, {}, false);
    double drop = 0;
    for (double psnr : q.psnr) drop += 10 * std::log10(1 + std::pow(10.0, (30.0 - psnr) / 10)) / double(q.psnr.size());
    EXPECT_NEAR(result.drop, drop, 1e-9);
}

TEST_F(QualityBudget, AgainstPhotosMeasuresTheDropFromTheUnprunedScene) {
    const GaussianCloud cloud = random_scene(62, 600, 0);
    Renderer renderer(context());
    // "Photos": the renders with a fixed pattern of noise, so the unpruned scene scores about 34 dB.
    eval::TestViews views = eval::render_targets(renderer, cloud, cameras(), {});
    views.photos = true;
    for (auto& target : views.targets)
        for (size_t i = 0; i < target.size(); ++i) target[i] += (i % 7 < 3 ? 0.02f : -0.02f);

    const auto scores = prune::score(cloud, {}, prune::ScoreMethod::opacity);
    const prune::Ranking ranking(scores, prune::keep_all(cloud.size()));
    prune::QualityBudget budget;
    budget.max_psnr_drop = 0.5;
    const prune::BudgetResult result = prune::fit_quality_budget(renderer, cloud, ranking, views, budget, {});
    EXPECT_GT(result.baseline_psnr, 30.0);
    EXPECT_LT(result.baseline_psnr, 40.0);
    EXPECT_TRUE(result.met);
    EXPECT_LE(result.drop, 0.5);
    EXPECT_NEAR(result.drop, result.baseline_psnr - result.psnr, 1e-12);
    EXPECT_LT(result.kept, cloud.size());
    expect_bisection(result, cloud.size(), 0);
}

TEST_F(QualityBudget, ShReductionKeepsTheLowestDegreeWithinBudget) {
    Renderer renderer(context());
    const auto test = [&](const GaussianCloud& cloud) {
        const eval::TestViews views = eval::render_targets(renderer, cloud, cameras(), {});
        const auto scores = prune::score(cloud, {}, prune::ScoreMethod::opacity);
        prune::QualityBudget budget;
        budget.max_psnr_drop = 0.01;
        budget.allow_sh_reduction = true;
        return prune::fit_quality_budget(renderer, cloud, prune::Ranking(scores, prune::keep_all(cloud.size())),
                                         views, budget, {});
    };
    // Degree 3 in name only (the higher bands are zero): every lower degree looks the same.
    const prune::BudgetResult flat = test(random_scene(63, 300, 0).with_sh_degree(3));
    EXPECT_EQ(flat.sh_degree, 0);
    ASSERT_GE(flat.probes.size(), 4u);
    for (int degree = 2, p = int(flat.probes.size()) - 3; degree >= 0; --degree, ++p) {
        EXPECT_EQ(flat.probes[size_t(p)].sh_degree, degree);
        EXPECT_EQ(flat.probes[size_t(p)].kept, flat.kept);
    }
    // Strong view-dependent colour: dropping bands costs far more than 0.01 dB; one try, then stop.
    const prune::BudgetResult shiny = test(random_scene(64, 300, 3));
    EXPECT_EQ(shiny.sh_degree, 3);
    EXPECT_EQ(shiny.probes.back().sh_degree, 2);
    EXPECT_FALSE(shiny.probes.back().meets);
}

TEST_F(QualityBudget, WhenEvenAllCandidatesMissTheBudgetItSaysSo) {
    const GaussianCloud cloud = random_scene(65, 200, 0);
    Renderer renderer(context());
    const eval::TestViews views = eval::render_targets(renderer, cloud, cameras(), {});
    const auto scores = prune::score(cloud, {}, prune::ScoreMethod::opacity);
    // Half the scene left as candidates (as if a lossless pass had dropped the rest): far over 0 dB.
    prune::KeepMask half(cloud.size(), 0);
    for (size_t i = 0; i < half.size(); i += 2) half[i] = 1;
    prune::QualityBudget budget;
    budget.max_psnr_drop = 0.0;
    const prune::BudgetResult result =
        prune::fit_quality_budget(renderer, cloud, prune::Ranking(scores, half), views, budget, {});
    EXPECT_FALSE(result.met);
    EXPECT_EQ(result.probes.size(), 1u);
    EXPECT_EQ(result.keep, half);
    budget.max_psnr_drop = -1;
    EXPECT_THROW(prune::fit_quality_budget(renderer, cloud, prune::Ranking(scores, half), views, budget, {}),
                 InputError);
}

}  // namespace
}  // namespace vksplat::test
