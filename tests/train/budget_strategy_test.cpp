// Training to a budget (train::BudgetStrategy): the growth schedule and the importance cut on the
// host, Trainer::remove on lavapipe, and a whole run's counts against the schedule.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <vector>

#include "vksplat/train/budget_strategy.hpp"
#include "vksplat/train/training_loop.hpp"
#include "train/photographed_views.hpp"

namespace vksplat::test {
namespace {

train::BudgetSchedule budget_of(size_t start, size_t budget, double exponent, double reach = 1.0) {
    train::BudgetSchedule b;
    b.start = start;
    b.budget = budget;
    b.growth_exponent = exponent;
    b.reach = reach;
    b.peak = 1.0;
    b.settle_rounds = 1;
    b.restart_decay = false;
    return b;
}

TEST(GrowthTarget, RisesFromTheStartToTheBudgetOverTheWindow) {
    const train::ReferenceSchedule reference;  // densify 500 .. 15,000
    const auto even = budget_of(1000, 11000, 1.0);
    EXPECT_EQ(train::growth_target(reference, even, 100), 1000u);
    EXPECT_EQ(train::growth_target(reference, even, 500), 1000u);
    EXPECT_EQ(train::growth_target(reference, even, 7750), 6000u);
    EXPECT_EQ(train::growth_target(reference, even, 15000), 11000u);
    EXPECT_EQ(train::growth_target(reference, even, 29000), 11000u);
    // Exponent 2 grows three quarters of the way by the window's middle.
    EXPECT_EQ(train::growth_target(reference, budget_of(1000, 11000, 2.0), 7750), 8500u);
    // Reach 0.5: the budget by the window's middle, held from there.
    EXPECT_EQ(train::growth_target(reference, budget_of(1000, 11000, 1.0, 0.5), 7750), 11000u);
    EXPECT_EQ(train::growth_target(reference, budget_of(1000, 11000, 1.0, 0.5), 4125), 6000u);
    // Never below the start's count, never above the budget; a budget below the start is the budget.
    for (uint64_t i = 0; i < 30000; i += 100) {
        const size_t t = train::growth_target(reference, budget_of(1000, 11000, 2.0), i);
        EXPECT_GE(t, 1000u);
        EXPECT_LE(t, 11000u);
    }
    EXPECT_EQ(train::growth_target(reference, budget_of(5000, 3000, 2.0), 100), 3000u);
    // A peak of 2 grows to twice the budget.
    auto twice = budget_of(1000, 11000, 1.0);
    twice.peak = 2.0;
    EXPECT_EQ(train::growth_target(reference, twice, 7750), 11500u);
    EXPECT_EQ(train::growth_target(reference, twice, 15000), 22000u);
}

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

TEST(BudgetStrategy, RefusesSettingsItCannotFollow) {
    const train::ReferenceSchedule reference;
    EXPECT_THROW(train::BudgetStrategy(reference, budget_of(10, 0, 2.0), {}), std::invalid_argument);
    EXPECT_THROW(train::BudgetStrategy(reference, budget_of(10, 100, 0.0), {}), std::invalid_argument);
    EXPECT_THROW(train::BudgetStrategy(reference, budget_of(10, 100, 2.0, 1.5), {}), std::invalid_argument);
    auto pruning = budget_of(10, 100, 2.0);
    pruning.prune_ratio = 0.2;
    EXPECT_THROW(train::BudgetStrategy(reference, pruning, {}), std::invalid_argument);
}

class BudgetTraining : public PhotographedViews {
protected:
    BudgetTraining() : PhotographedViews(60) {}
};

// Removing Gaussians keeps the others' parameters, in order; the survivors keep training.
TEST_F(BudgetTraining, RemoveKeepsTheOthersAsTheyWere) {
    train::Trainer trainer(context(), truth, {});
    for (int i = 0; i < 3; ++i) trainer.step(cameras[size_t(i)], photos.at(size_t(i)));
    const GaussianCloud before = trainer.cloud();
    std::vector<uint8_t> keep(before.size(), 1);
    for (size_t i = 0; i < keep.size(); i += 3) keep[i] = 0;
    EXPECT_EQ(trainer.remove(keep), (keep.size() + 2) / 3);
    const GaussianCloud after = trainer.cloud();
    const GaussianCloud expected = before.subset(keep);
    ASSERT_EQ(after.size(), expected.size());
    EXPECT_EQ(after.positions, expected.positions);
    EXPECT_EQ(after.sh, expected.sh);
    EXPECT_EQ(after.opacity_logits, expected.opacity_logits);
    EXPECT_TRUE(trainer.step(cameras[0], photos.at(0)).applied);
    EXPECT_THROW(trainer.remove(std::vector<uint8_t>(3, 1)), std::invalid_argument);
}

// A short run on the reference's schedule, scaled down: the count never passes the schedule's
// target after a densification, importance prunes at the opacity resets inside the window, the
// count passes the budget on the way to its peak and settles to it after the window.
TEST_F(BudgetTraining, CountsFollowTheScheduleAndPrunesHappenAtResets) {
    train::ReferenceSchedule reference;
    reference.sh_degree = 1;
    reference.sh_degree_interval = 20;
    reference.densify_from = 10;
    reference.densify_until = 100;
    reference.densify_interval = 10;
    reference.opacity_reset_interval = 40;
    reference.densify.grad_threshold = 0;  // every drawn Gaussian may grow
    auto budget = budget_of(20, 90, 2.0);
    budget.min_gradient = 0;
    budget.prune_ratio = 0.25;
    budget.peak = 1.5;        // grows to 135, settles back to 90 after step 100
    budget.settle_at = 100;
    std::vector<uint64_t> scored_at;
    std::vector<uint8_t> every_third(60, 0);
    for (size_t i = 0; i < 60; i += 3) every_third[i] = 1;
    train::Trainer trainer(context(), truth.subset(every_third), {});
    train::BudgetStrategy strategy(reference, budget, [&](const GaussianCloud& cloud) {
        scored_at.push_back(trainer.iteration());
        std::vector<float> importance(cloud.size());
        for (size_t i = 0; i < cloud.size(); ++i) importance[i] = cloud.opacity_logits[i];
        return importance;
    });
    train::LoopOptions options;
    options.iterations = 120;
    std::map<uint64_t, size_t> counts;
    options.snapshot_every = 10;
    options.snapshot = [&](const train::Trainer& t, uint64_t iteration) { counts[iteration] = t.size(); };
    train::run_training_loop(trainer, strategy, cameras, views, photos, options);
    EXPECT_EQ(scored_at, (std::vector<uint64_t>{40, 80, 100}));  // the resets at 40 and 80, the settling
    EXPECT_EQ(strategy.events().prune_events, 3u);
    EXPECT_GT(strategy.events().pruned, 0u);
    for (const auto& [iteration, count] : counts)
        if (iteration > reference.densify_from && iteration < reference.densify_until) {
            EXPECT_LE(count, train::growth_target(reference, budget, iteration)) << "at " << iteration;
        }
    EXPECT_GT(counts.at(90), 90u);
    EXPECT_EQ(counts.at(100), 90u);
    EXPECT_EQ(trainer.size(), 90u);
}

// Settling in rounds: each round re-scores and keeps its geometric share; the last reaches the
// budget and nothing is scored after it.
TEST_F(BudgetTraining, SettlesInRoundsWhenAsked) {
    train::ReferenceSchedule reference;
    reference.sh_degree = 0;
    reference.densify_from = 10;
    reference.densify_until = 60;
    reference.densify_interval = 10;
    reference.opacity_reset_interval = 1000;
    reference.densify.grad_threshold = 0;
    auto budget = budget_of(20, 40, 1.0);
    budget.min_gradient = 0;
    budget.peak = 2.0;
    budget.settle_at = 60;
    budget.settle_rounds = 2;
    budget.settle_spacing = 15;
    budget.restart_decay = true;
    budget.iterations = 100;  // the restarted decay runs over the 40 steps after the settling
    std::vector<uint64_t> scored_at;
    std::vector<size_t> scored_sizes;
    std::vector<uint8_t> every_third(60, 0);
    for (size_t i = 0; i < 60; i += 3) every_third[i] = 1;
    train::Trainer trainer(context(), truth.subset(every_third), {});
    train::BudgetStrategy strategy(reference, budget, [&](const GaussianCloud& cloud) {
        scored_at.push_back(trainer.iteration());
        scored_sizes.push_back(cloud.size());
        std::vector<float> importance(cloud.size());
        for (size_t i = 0; i < cloud.size(); ++i) importance[i] = cloud.opacity_logits[i];
        return importance;
    });
    train::LoopOptions options;
    options.iterations = 100;
    std::map<uint64_t, size_t> counts;
    options.snapshot_every = 5;
    std::map<uint64_t, double> rates;
    options.snapshot = [&](const train::Trainer& t, uint64_t iteration) {
        counts[iteration] = t.size();
        rates[iteration] = t.position_learning_rate();
    };
    train::run_training_loop(trainer, strategy, cameras, views, photos, options);
    ASSERT_EQ(scored_at, (std::vector<uint64_t>{60, 75}));
    // The position rate decays as usual until the settling, then afresh over 40 steps: half-way
    // (log-linear) at 80, the final rate from 100 on.
    const train::LearningRates r;
    EXPECT_NEAR(rates.at(50), r.position_initial * std::pow(r.position_final / r.position_initial, 50.0 / 30000), 1e-12);
    EXPECT_NEAR(rates.at(80), std::sqrt(r.position_initial * r.position_final), 1e-12);
    EXPECT_NEAR(rates.at(100), r.position_final, 1e-12);
    EXPECT_GT(scored_sizes[0], 40u);
    EXPECT_EQ(counts.at(60), train::settle_target(scored_sizes[0], 40, 2));
    EXPECT_GT(counts.at(60), 40u);
    EXPECT_EQ(counts.at(70), counts.at(60));
    EXPECT_EQ(counts.at(75), 40u);
    EXPECT_EQ(trainer.size(), 40u);
    EXPECT_EQ(strategy.events().prune_events, 2u);
}

}  // namespace
}  // namespace vksplat::test
