// Settling inside training (train::Settling): the counts it keeps, on the host, and on lavapipe the
// reference recipe settling to a share of the importance, and what scoring holds in device memory.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <vector>

#include "vksplat/jobs/train_scene.hpp"
#include "vksplat/prune/accumulate.hpp"
#include "vksplat/prune/scores.hpp"
#include "vksplat/train/strategy.hpp"
#include "vksplat/train/training_loop.hpp"
#include "train/photographed_views.hpp"

namespace vksplat::test {
namespace {

TEST(SettleTarget, StepsGeometricallyToTheBudget) {
    // 160,000 to 80,000 in three rounds: x 2^(-1/3) each time.
    EXPECT_EQ(train::settle_target(160000, 80000, 3), 126992u);
    EXPECT_EQ(train::settle_target(126992, 80000, 2), 100794u);
    EXPECT_EQ(train::settle_target(100794, 80000, 1), 80000u);
    EXPECT_EQ(train::settle_target(160000, 80000, 1), 80000u);
    // Within the budget nothing goes.
    EXPECT_EQ(train::settle_target(70000, 80000, 3), 70000u);
    EXPECT_EQ(train::settle_target(80000, 80000, 2), 80000u);
}

TEST(KeepMostImportant, DropsTheLowestWithTiesByIndexAndNaNFirst) {
    const std::vector<float> importance = {0.5f, 0.1f, NAN, 0.1f, 0.9f, 0.3f};
    EXPECT_EQ(train::keep_most_important(importance, 3), (std::vector<uint8_t>{1, 0, 0, 0, 1, 1}));
    EXPECT_EQ(train::keep_most_important(importance, 4), (std::vector<uint8_t>{1, 0, 0, 1, 1, 1}));
    EXPECT_EQ(train::keep_most_important(importance, 6), (std::vector<uint8_t>(6, 1)));
    // One is always kept.
    EXPECT_EQ(train::keep_most_important({0.2f, 0.7f}, 0), (std::vector<uint8_t>{0, 1}));
}

TEST(CountCarrying, CountsTheMostImportantUntilTheShareIsReached) {
    const std::vector<float> importance = {1.0f, 6.0f, 0.5f, 2.0f, 0.5f};  // total 10
    EXPECT_EQ(train::count_carrying(importance, 0.6), 1u);    // 6
    EXPECT_EQ(train::count_carrying(importance, 0.61), 2u);   // 6 + 2
    EXPECT_EQ(train::count_carrying(importance, 0.9), 3u);    // 6 + 2 + 1
    EXPECT_EQ(train::count_carrying(importance, 0.95), 4u);
    EXPECT_EQ(train::count_carrying(importance, 1.0), 5u);
    // NaN and negative carry nothing; at least one is counted even when nothing carries any.
    EXPECT_EQ(train::count_carrying({NAN, 3.0f, -5.0f, 1.0f}, 0.75), 1u);
    EXPECT_EQ(train::count_carrying({0.0f, 0.0f}, 0.5), 1u);
    EXPECT_THROW(train::count_carrying(importance, 0.0), std::invalid_argument);
    EXPECT_THROW(train::count_carrying(importance, 1.5), std::invalid_argument);
}

TEST(Settling, RefusesATargetItCannotReach) {
    const auto importance = [](const GaussianCloud& c) { return std::vector<float>(c.size(), 1.0f); };
    EXPECT_THROW(train::Settling({}, {}, importance), std::invalid_argument);
    EXPECT_THROW(train::Settling({}, {.share = 1.5}, importance), std::invalid_argument);
    train::SettleSchedule apart;
    apart.spacing = 0;
    EXPECT_THROW(train::Settling(apart, {.share = 0.9}, importance), std::invalid_argument);
}

class ReferenceSettling : public PhotographedViews {
protected:
    ReferenceSettling() : PhotographedViews(60) {}
    // The photographed views as a training run's data, for jobs::settling_importance.
    jobs::TrainingData training_data() const {
        jobs::TrainingData data;
        data.cameras = cameras;
        data.train_views = views;
        return data;
    }
};

// The reference recipe, scaled down, settling to the Gaussians that carry 80% of the importance
// (opacity here) in two rounds: before the first round it densifies as the reference does; each
// round keeps the geometric share of the way to the count carrying 80% of that round's scores, and
// the last keeps exactly that count.
TEST_F(ReferenceSettling, KeepsTheGaussiansCarryingTheShare) {
    train::ReferenceSchedule reference;
    reference.sh_degree = 0;
    reference.densify_from = 10;
    reference.densify_until = 60;
    reference.densify_interval = 10;
    reference.opacity_reset_interval = 1000;
    reference.densify.grad_threshold = 0;  // every drawn Gaussian grows
    train::SettleSchedule schedule;
    schedule.at = 60;
    schedule.rounds = 2;
    schedule.spacing = 20;
    schedule.iterations = 100;
    std::vector<std::vector<float>> scored;
    const train::Importance importance = [&](const GaussianCloud& cloud) {
        scored.push_back(prune::opacities(cloud));
        return scored.back();
    };
    train::ReferenceStrategy strategy(reference, train::Settling(schedule, {.share = 0.8}, importance));
    train::Trainer trainer(context(), truth, {});
    std::map<uint64_t, size_t> counts;
    train::LoopOptions options;
    options.iterations = 100;
    options.snapshot_every = 10;
    options.snapshot = [&](const train::Trainer& t, uint64_t iteration) { counts[iteration] = t.size(); };
    train::run_training_loop(trainer, strategy, cameras, views, photos, options);

    ASSERT_EQ(scored.size(), 2u);
    EXPECT_GT(scored[0].size(), truth.size());  // densification grew the scene first
    const size_t first = train::count_carrying(scored[0], 0.8);
    ASSERT_LT(first, scored[0].size());
    EXPECT_EQ(counts.at(60), train::settle_target(scored[0].size(), first, 2));
    EXPECT_EQ(scored[1].size(), counts.at(60));
    EXPECT_EQ(counts.at(80), train::count_carrying(scored[1], 0.8));
    EXPECT_EQ(trainer.size(), counts.at(80));
    EXPECT_EQ(strategy.events().prune_events, 2u);
    EXPECT_EQ(strategy.events().pruned, scored[0].size() - trainer.size());
}

// The recipes' importance (jobs::settling_importance) renders the scene without its higher SH bands:
// blend weights do not depend on colour, so the scores are those of the scene as it is.
TEST_F(ReferenceSettling, ScoringWithoutColourGivesTheScoresOfTheScene) {
    // The scene's higher bands carry colour, which the scoring leaves out.
    ASSERT_NE(truth.with_sh_degree(0).with_sh_degree(truth.sh_degree).sh, truth.sh);
    const jobs::TrainingData data = training_data();
    jobs::TrainOptions options;
    RenderSettings settings;
    settings.background = options.background;
    for (prune::ScoreMethod method : {prune::ScoreMethod::blend, prune::ScoreMethod::blend_mix}) {
        options.recipe.budget_score = method;
        const std::vector<float> scored = jobs::settling_importance(context(), data, options)(truth);
        const prune::ViewTotals totals = prune::accumulate(renderer, truth, cameras, views, settings);
        EXPECT_EQ(scored, prune::score(truth, totals, method, options.seed)) << prune::to_string(method);
    }
}

// Scoring renders every training view with a renderer of its own: the trainer's frame is freed
// first, so that a settling round holds no more device memory than a step does.
TEST_F(ReferenceSettling, ScoringHoldsNoMoreThanAStep) {
    train::Trainer trainer(context(), truth, {});
    for (size_t v : views) trainer.step(cameras[v], photos.at(v));
    const uint64_t step_bytes = context().held_device_bytes();
    const jobs::TrainingData data = training_data();
    const train::Importance importance = jobs::settling_importance(context(), data, {});
    context().reset_peak_device_bytes();
    train::ImportancePrunes events;
    train::remove_least_important(trainer, importance, events,
                                  [](const std::vector<float>& scores) { return scores.size() / 2; });
    EXPECT_EQ(trainer.size(), truth.size() / 2);
    EXPECT_LE(context().peak_device_bytes(), step_bytes)
        << "step " << step_bytes << " bytes, scoring and removal " << context().peak_device_bytes();
}

}  // namespace
}  // namespace vksplat::test
