// How much a re-fit spends: the iterations prune --recover takes by the fraction dropped when none
// are asked for, and a wall-time budget (--recover-seconds, finetune --seconds) that is turned into
// steps, shared by the rounds, and stops the run long before an iteration count it replaces would.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/io_test_helpers.hpp"
#include "jobs/rendered_photos.hpp"
#include "support/gpu_fixture.hpp"
#include "support/scenes.hpp"
#include "vksplat/jobs/finetune.hpp"
#include "vksplat/jobs/prune_recover.hpp"
#include "vksplat/prune/accumulate.hpp"

namespace vksplat::test {
namespace {

using io::test::expect_input_error;

TEST(DefaultRecoverIterations, GrowWithTheFractionDropped) {
    EXPECT_EQ(jobs::default_recover_iterations(0.0), 5000u);
    EXPECT_EQ(jobs::default_recover_iterations(0.5), 5000u);
    EXPECT_EQ(jobs::default_recover_iterations(0.65), 28000u);  // halfway to 50,000, in whole thousands
    EXPECT_EQ(jobs::default_recover_iterations(0.8), 50000u);
    EXPECT_EQ(jobs::default_recover_iterations(0.85), 55000u);
    EXPECT_EQ(jobs::default_recover_iterations(0.9), 60000u);
    EXPECT_EQ(jobs::default_recover_iterations(0.99), 60000u);
    EXPECT_EQ(jobs::default_recover_iterations(1.0), 60000u);
    uint64_t previous = 0;
    for (double dropped = 0; dropped <= 1.0; dropped += 0.01) {
        const uint64_t iterations = jobs::default_recover_iterations(dropped);
        EXPECT_GE(iterations, previous) << dropped;
        EXPECT_EQ(iterations % 1000, 0u) << dropped;
        previous = iterations;
    }
}

// Each round takes an equal share of what is left, so one that overran shortens the later ones and
// the rounds together end with the budget.
TEST(RoundSeconds, ShareWhatIsLeftSoThatOverrunsComeOutOfLaterRounds) {
    EXPECT_DOUBLE_EQ(jobs::round_seconds(60, 1, 3), 20);
    EXPECT_DOUBLE_EQ(jobs::round_seconds(35, 2, 3), 17.5);  // round 1 took 25 s
    EXPECT_DOUBLE_EQ(jobs::round_seconds(17.5, 3, 3), 17.5);
    EXPECT_DOUBLE_EQ(jobs::round_seconds(60, 1, 1), 60);
    double left = 60;
    for (int round = 1; round <= 4; ++round) left -= jobs::round_seconds(left, round, 4);
    EXPECT_NEAR(left, 0, 1e-9);
}

// Spaced rounds: each before the last takes at most kSpacedRoundShare of what is left, the last
// all of it, and the rounds still end with the budget.
TEST(RoundSeconds, SpacedRoundsLeaveMostOfTheTimeToTheLast) {
    EXPECT_DOUBLE_EQ(jobs::round_seconds(60, 1, 5, true), 60 * jobs::kSpacedRoundShare);
    EXPECT_DOUBLE_EQ(jobs::round_seconds(40, 5, 5, true), 40);
    EXPECT_DOUBLE_EQ(jobs::round_seconds(1, 1, 2, true), 0.05);
    double left = 60;
    for (int round = 1; round <= 5; ++round) left -= jobs::round_seconds(left, round, 5, true);
    EXPECT_NEAR(left, 0, 1e-9);
}

TEST(PlannedIterations, FillTheBudgetAtTheTimedStep) {
    EXPECT_EQ(jobs::planned_iterations(10, 0.0005), 20000u);
    EXPECT_EQ(jobs::planned_iterations(10, 3), 3u);
    EXPECT_EQ(jobs::planned_iterations(0.01, 3), 1u);  // a re-fit takes a step however short its budget
    EXPECT_EQ(jobs::planned_iterations(-2, 3), 1u);     // the budget already spent timing the steps
    EXPECT_EQ(jobs::planned_iterations(1e9, 1e-9), uint64_t(1) << 30);
}

class RecoverBudget : public GpuTest {
protected:
    RecoverBudget() : renderer(context()) {
        truth = random_scene(5, 200, 1, 4.0f, 6.0f, 0.05f, 0.2f, 1.0f);
        renderer.set_scene(truth);
        options.test_views = {0};
    }
    Renderer renderer;
    GaussianCloud truth;
    std::vector<Camera> cameras = row_of_five_views();
    jobs::PhotoSource photos = rendered_photos(renderer);
    jobs::FinetuneOptions options;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

TEST_F(RecoverBudget, RefusesBudgetsThatAreNotPositiveSecondsBeforeAnyStep) {
    for (const double seconds : {0.0, -3.0, std::numeric_limits<double>::quiet_NaN(),
                                 std::numeric_limits<double>::infinity()}) {
        auto o = options;
        o.seconds = seconds;
        expect_input_error([&] { jobs::finetune_scene(context(), truth, cameras, photos, o); },
                           {"--seconds", "must be a finite number of seconds above 0"});
        jobs::RecoverOptions recover;
        recover.seconds = seconds;
        expect_input_error([&] { jobs::check_recover(recover, cameras, photos); },
                           {"--recover-seconds", "must be a finite number of seconds above 0"});
    }
    jobs::RecoverOptions both;
    both.seconds = 60;
    both.iterations = 5000;
    expect_input_error([&] { jobs::check_recover(both, cameras, photos); },
                       {"--recover-seconds 60", "give --recover 5000 or the seconds, not both"});
    auto resumed = options;
    resumed.seconds = 5;
    resumed.resume = true;
    expect_input_error([&] { jobs::finetune_scene(context(), truth, cameras, photos, resumed); },
                       {"--resume", "give --iters, not --seconds"});
}

// On lavapipe a step of this scene takes milliseconds, so a billion iterations would take weeks:
// the budget, not the count, ends the run, which still finishes (not interrupted) and measures.
// It runs until the deadline, whatever count the timed steps planned (that count sets only the
// position rate's decay).
TEST_F(RecoverBudget, ATimeBudgetEndsTheRefitInsteadOfItsIterationCount) {
    auto o = options;
    o.iterations = 1'000'000'000;
    o.seconds = 2;
    const jobs::QualityProbe quality = [](const GaussianCloud&) { return eval::Quality{}; };
    const auto start = std::chrono::steady_clock::now();
    // Fails rather than hangs where the budget is not kept.
    const auto give_up = [](const train::LoopStatus& s) {
        if (s.seconds > 60) throw std::runtime_error("still re-fitting after 60 s");
    };
    const jobs::FinetuneResult result = jobs::finetune_scene(context(), truth, cameras, photos, o, quality, give_up);
    const double seconds = seconds_since(start);
    EXPECT_FALSE(result.interrupted);
    EXPECT_TRUE(result.after.has_value());
    EXPECT_GE(result.iterations, 1u);
    EXPECT_LT(result.planned_iterations, 1'000'000u);
    EXPECT_GE(seconds, 2.0) << "the run ended before its deadline";
    EXPECT_LT(seconds, 30) << "a 2 s budget ran " << seconds << " s";
}

TEST_F(RecoverBudget, TheRoundsShareOneBudget) {
    const prune::ViewTotals totals = prune::accumulate(renderer, truth, cameras, {1, 2, 3, 4}, RenderSettings{});
    const std::vector<float> scores = prune::score(truth, totals, prune::ScoreMethod::blend);
    jobs::RecoverOptions recover;
    recover.seconds = 3;
    recover.rounds = 3;
    recover.finetune = options;
    const auto start = std::chrono::steady_clock::now();
    const jobs::RecoverResult result = jobs::prune_and_recover(context(), renderer, truth, scores,
                                                               prune::lossless_mask(totals), truth.size() / 5, cameras,
                                                               photos, recover);
    const double seconds = seconds_since(start);
    ASSERT_EQ(result.rounds.size(), 3u);
    for (const jobs::RecoverRound& round : result.rounds) EXPECT_GE(round.refit.iterations, 1u);
    EXPECT_GE(seconds, 3.0) << "the rounds ended before the budget's deadline";
    EXPECT_LT(seconds, 30) << "a 3 s budget over 3 rounds ran " << seconds << " s";
}

// A size budget drops SH bands before the last round's re-fit (prune_scene), through
// RecoverOptions::before_last_refit: it sees the last round's model at its count with that model's
// blend weights, once, and what it returns is what the last round re-fits.
TEST_F(RecoverBudget, TheLastRoundReFitsWhatBeforeLastRefitMadeOfItsModel) {
    const prune::ViewTotals totals = prune::accumulate(renderer, truth, cameras, {1, 2, 3, 4}, RenderSettings{});
    const std::vector<float> scores = prune::score(truth, totals, prune::ScoreMethod::blend);
    jobs::RecoverOptions recover;
    recover.iterations = 4;
    recover.rounds = 2;
    recover.finetune = options;
    const size_t keep = truth.size() / 5;
    int calls = 0;
    recover.before_last_refit = [&](const GaussianCloud& model, std::span<const double> blend) {
        ++calls;
        EXPECT_EQ(model.size(), keep);
        EXPECT_EQ(blend.size(), model.size());
        EXPECT_GT(*std::max_element(blend.begin(), blend.end()), 0.0);
        GaussianCloud dark = model;
        const size_t stride = size_t(dark.sh_coefficients()) * 3;
        for (size_t i = 0; i < dark.size(); ++i) std::fill_n(&dark.sh[i * stride + 3], stride - 3, 0.0f);
        return dark;
    };
    const jobs::RecoverResult result = jobs::prune_and_recover(context(), renderer, truth, scores,
                                                               prune::lossless_mask(totals), keep, cameras, photos, recover);
    EXPECT_EQ(calls, 1);
    ASSERT_EQ(result.cloud.size(), keep);
    // Two re-fit steps move a coefficient by about two of its learning rate (Adam), far less than
    // the scene's own higher SH, which the hook zeroed.
    const auto largest_higher_sh = [](const GaussianCloud& cloud) {
        const size_t stride = size_t(cloud.sh_coefficients()) * 3;
        float largest = 0.0f;
        for (size_t i = 0; i < cloud.size(); ++i)
            for (size_t k = 3; k < stride; ++k) largest = std::max(largest, std::abs(cloud.sh[i * stride + k]));
        return largest;
    };
    EXPECT_LT(largest_higher_sh(result.cloud), 0.01f);
    EXPECT_GT(largest_higher_sh(truth), 0.1f);
}

}  // namespace
}  // namespace vksplat::test
