// Training to a budget (train::BudgetStrategy): the growth schedule and the importance cut on the
// host, Trainer::remove on lavapipe, and a whole run's counts against the schedule.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "vksplat/prune/scores.hpp"
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
    b.settle.rounds = 1;
    b.settle.restart_decay = false;
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
    // The peak limit stops the growth beyond the budget, never the growth to it.
    twice.peak_limit = 16000;
    EXPECT_EQ(train::peak_count(twice), 16000u);
    EXPECT_EQ(train::growth_target(reference, twice, 7750), 8500u);
    EXPECT_EQ(train::growth_target(reference, twice, 15000), 16000u);
    twice.peak_limit = 5000;
    EXPECT_EQ(train::peak_count(twice), 11000u);
    EXPECT_EQ(train::growth_target(reference, twice, 15000), 11000u);
}

TEST(GrowthTarget, TheDefaultPeakIsThreeTimesASmallBudgetAndNoMoreThanALargeOne) {
    train::BudgetSchedule b;
    b.budget = 40000;
    EXPECT_EQ(train::peak_count(b), 120000u);
    b.budget = 80000;
    EXPECT_EQ(train::peak_count(b), 240000u);
    b.budget = 200000;
    EXPECT_EQ(train::peak_count(b), 400000u);
    b.budget = 400000;
    EXPECT_EQ(train::peak_count(b), 400000u);
    b.budget = 1000000;
    EXPECT_EQ(train::peak_count(b), 1000000u);
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

    // What a run of the strategy did: when it scored (and how many it scored), and the count and
    // position rate at every snapshot.
    struct Run {
        std::vector<uint64_t> scored_at;
        std::vector<size_t> scored_sizes;
        std::map<uint64_t, size_t> counts;
        std::map<uint64_t, double> rates;
        std::map<uint64_t, float> max_opacity;
        float final_max_scale = 0;
        train::ImportancePrunes events;
        size_t final_count = 0;
    };
    // The reference's schedule scaled down to a hundred steps: densification every 10 steps from
    // step 10, every drawn Gaussian a candidate.
    static train::ReferenceSchedule scaled_schedule(uint64_t densify_until, uint64_t reset_interval, int sh_degree) {
        train::ReferenceSchedule reference;
        reference.sh_degree = sh_degree;
        reference.sh_degree_interval = 20;
        reference.densify_from = 10;
        reference.densify_until = densify_until;
        reference.densify_interval = 10;
        reference.opacity_reset_interval = reset_interval;
        reference.densify.grad_threshold = 0;
        return reference;
    }
    // Every third Gaussian of the truth.
    GaussianCloud every_third() const {
        std::vector<uint8_t> keep(truth.size(), 0);
        for (size_t i = 0; i < keep.size(); i += 3) keep[i] = 1;
        return truth.subset(keep);
    }
    // Trains from every third Gaussian of the truth (or from `start`), scoring importance by opacity.
    Run run(const train::ReferenceSchedule& reference, const train::BudgetSchedule& budget, uint64_t iterations,
            uint64_t snapshot_every) {
        return run(reference, budget, iterations, snapshot_every, every_third());
    }
    Run run(const train::ReferenceSchedule& reference, const train::BudgetSchedule& budget, uint64_t iterations,
            uint64_t snapshot_every, const GaussianCloud& start) {
        Run out;
        train::Trainer trainer(context(), start, {});
        train::BudgetStrategy strategy(reference, budget, [&](const GaussianCloud& cloud) {
            out.scored_at.push_back(trainer.iteration());
            out.scored_sizes.push_back(cloud.size());
            std::vector<float> importance(cloud.size());
            for (size_t i = 0; i < cloud.size(); ++i) importance[i] = cloud.opacity_logits[i];
            return importance;
        });
        train::LoopOptions options;
        options.iterations = iterations;
        options.snapshot_every = snapshot_every;
        options.snapshot = [&](const train::Trainer& t, uint64_t iteration) {
            out.counts[iteration] = t.size();
            out.rates[iteration] = t.position_learning_rate();
            const std::vector<float> opacity = prune::opacities(t.cloud());
            out.max_opacity[iteration] = *std::max_element(opacity.begin(), opacity.end());
        };
        train::run_training_loop(trainer, strategy, cameras, views, photos, options);
        out.events = strategy.events();
        out.final_count = trainer.size();
        for (float log_scale : trainer.cloud().log_scales) out.final_max_scale = std::max(out.final_max_scale, std::exp(log_scale));
        return out;
    }
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
    const train::ReferenceSchedule reference = scaled_schedule(100, 40, 1);
    auto budget = budget_of(20, 90, 2.0);
    budget.min_gradient = 0;
    budget.prune_ratio = 0.25;
    budget.peak = 1.5;        // grows to 135, settles back to 90 after step 100
    budget.settle.at = 100;
    const Run r = run(reference, budget, 120, 10);
    EXPECT_EQ(r.scored_at, (std::vector<uint64_t>{40, 80, 100}));  // the resets at 40 and 80, the settling
    EXPECT_EQ(r.events.prune_events, 3u);
    EXPECT_GT(r.events.pruned, 0u);
    for (const auto& [iteration, count] : r.counts)
        if (iteration > reference.densify_from && iteration < reference.densify_until) {
            EXPECT_LE(count, train::growth_target(reference, budget, iteration)) << "at " << iteration;
        }
    EXPECT_GT(r.counts.at(90), 90u);
    EXPECT_EQ(r.counts.at(100), 90u);
    EXPECT_EQ(r.final_count, 90u);
}

// The reference's opacity resets happen only when asked for: with them every opacity is at most
// the reset value right after the reset step; without them the scene keeps its opacities.
TEST_F(BudgetTraining, ResetsOpacityOnlyWhenAsked) {
    const train::ReferenceSchedule reference = scaled_schedule(60, 40, 0);
    auto budget = budget_of(20, 40, 1.0);
    budget.min_gradient = 0;
    budget.settle.at = 60;
    const Run without = run(reference, budget, 50, 40);
    EXPECT_GT(without.max_opacity.at(40), 0.1f);
    budget.reset_opacity = true;
    const Run with = run(reference, budget, 50, 40);
    EXPECT_LE(with.max_opacity.at(40), float(reference.opacity_reset_value) + 1e-6f);
    EXPECT_GT(with.max_opacity.at(50), with.max_opacity.at(40));  // and they grow back
}

// The reference's prune of Gaussians larger than max_world_scale x extent (1 here) happens only
// when asked for: a budget of the starting count grows nothing, so only prunes change the scene.
TEST_F(BudgetTraining, KeepsLargeGaussiansUnlessAsked) {
    const train::ReferenceSchedule reference = scaled_schedule(100, 10, 0);  // the large prune from step 20 on
    GaussianCloud start = every_third();
    const float large = float(4 * reference.densify.max_world_scale);
    for (size_t k = 0; k < 3; ++k) start.log_scales[k] = std::log(large);  // Gaussian 0
    start.opacity_logits[0] = 3.0f;  // not the transparency prune's
    auto budget = budget_of(start.size(), start.size(), 1.0);
    budget.settle.at = 100;
    const Run kept = run(reference, budget, 40, 10, start);
    EXPECT_EQ(kept.final_count, start.size());
    EXPECT_GT(kept.final_max_scale, float(reference.densify.max_world_scale));
    budget.prune_large = true;
    const Run pruned = run(reference, budget, 40, 10, start);
    EXPECT_LT(pruned.final_count, start.size());
    EXPECT_LE(pruned.final_max_scale, float(reference.densify.max_world_scale));
}

// Settling in rounds: each round re-scores and keeps its geometric share; the last reaches the
// budget and nothing is scored after it.
TEST_F(BudgetTraining, SettlesInRoundsWhenAsked) {
    const train::ReferenceSchedule reference = scaled_schedule(60, 1000, 0);
    auto budget = budget_of(20, 40, 1.0);
    budget.min_gradient = 0;
    budget.peak = 2.0;
    budget.settle.at = 60;
    budget.settle.rounds = 2;
    budget.settle.spacing = 15;
    budget.settle.restart_decay = true;
    budget.settle.iterations = 100;  // the restarted decay runs over the 40 steps after the settling
    const Run r = run(reference, budget, 100, 5);
    ASSERT_EQ(r.scored_at, (std::vector<uint64_t>{60, 75}));
    // The position rate decays as usual until the settling, then afresh over 40 steps: half-way
    // (log-linear) at 80, the final rate from 100 on.
    const train::LearningRates rates;
    EXPECT_NEAR(r.rates.at(50),
                rates.position_initial * std::pow(rates.position_final / rates.position_initial, 50.0 / 30000), 1e-12);
    EXPECT_NEAR(r.rates.at(80), std::sqrt(rates.position_initial * rates.position_final), 1e-12);
    EXPECT_NEAR(r.rates.at(100), rates.position_final, 1e-12);
    EXPECT_GT(r.scored_sizes[0], 40u);
    EXPECT_EQ(r.counts.at(60), train::settle_target(r.scored_sizes[0], 40, 2));
    EXPECT_GT(r.counts.at(60), 40u);
    EXPECT_EQ(r.counts.at(70), r.counts.at(60));
    EXPECT_EQ(r.counts.at(75), 40u);
    EXPECT_EQ(r.final_count, 40u);
    EXPECT_EQ(r.events.prune_events, 2u);
}

}  // namespace
}  // namespace vksplat::test
