// The one training loop and its strategies: the reference schedule step by step (train.py's
// constants), what the loop asks of a strategy, the view order a resume continues, and Ctrl-C.
#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <map>
#include <vector>

#include "vksplat/train/strategy.hpp"
#include "vksplat/train/training_loop.hpp"
#include "train/photographed_views.hpp"

namespace vksplat::test {
namespace {

namespace fs = std::filesystem;

// train.py: oneupSHdegree every 1000; densify when iteration > densify_from_iter and
// iteration % densification_interval == 0, size threshold once iteration > opacity_reset_interval;
// reset_opacity when iteration % opacity_reset_interval == 0 or (white background and
// iteration == densify_from_iter); none of it from densify_until_iter on.
TEST(ReferenceSchedule, MatchesTheReferenceTrainer) {
    const train::ReferenceSchedule schedule;
    EXPECT_EQ(train::scheduled_step(schedule, 1).sh_degree, 0);
    EXPECT_EQ(train::scheduled_step(schedule, 999).sh_degree, 0);
    EXPECT_EQ(train::scheduled_step(schedule, 1000).sh_degree, 1);
    EXPECT_EQ(train::scheduled_step(schedule, 29999).sh_degree, 3);
    EXPECT_FALSE(train::scheduled_step(schedule, 500).densify);
    EXPECT_TRUE(train::scheduled_step(schedule, 600).densify);
    EXPECT_FALSE(train::scheduled_step(schedule, 650).densify);
    EXPECT_FALSE(train::scheduled_step(schedule, 3000).prune_large);
    EXPECT_TRUE(train::scheduled_step(schedule, 3100).prune_large);
    EXPECT_TRUE(train::scheduled_step(schedule, 14900).densify);
    EXPECT_FALSE(train::scheduled_step(schedule, 15000).densify);
    EXPECT_TRUE(train::scheduled_step(schedule, 3000).reset_opacity);
    EXPECT_TRUE(train::scheduled_step(schedule, 12000).reset_opacity);
    EXPECT_FALSE(train::scheduled_step(schedule, 15000).reset_opacity);
    EXPECT_FALSE(train::scheduled_step(schedule, 500).reset_opacity);
    train::ReferenceSchedule white = schedule;
    white.white_background = true;
    EXPECT_TRUE(train::scheduled_step(white, 500).reset_opacity);
}

// The same seed gives the same order, a permutation of the views each epoch.
TEST(TrainingView, EachEpochIsAPermutationOfTheViews) {
    const std::vector<size_t> views = {2, 5, 7, 11};
    for (uint64_t epoch = 0; epoch < 3; ++epoch) {
        std::vector<size_t> seen;
        for (uint64_t i = 0; i < views.size(); ++i) seen.push_back(train::training_view(epoch * 4 + i, 9, views));
        std::sort(seen.begin(), seen.end());
        EXPECT_EQ(seen, views);
    }
    EXPECT_EQ(train::training_view(6, 9, views), train::training_view(6, 9, views));
}

// Records what the loop asks.
class RecordingStrategy final : public train::Strategy {
public:
    void before_step(train::Trainer&, uint64_t iteration) override { before.push_back(iteration); }
    void after_step(train::Trainer&, uint64_t iteration) override {
        after.push_back(iteration);
        if (stop_after && iteration == stop_after) stop->store(true);
    }
    std::vector<uint64_t> before, after;
    uint64_t stop_after = 0;
    std::atomic<bool>* stop = nullptr;
};

class TrainingLoop : public PhotographedViews {
protected:
    TrainingLoop() : PhotographedViews(30) {}
};

TEST_F(TrainingLoop, AsksTheStrategyAroundEveryStepAndReportsTheLast) {
    train::Trainer trainer(context(), truth, {});
    RecordingStrategy strategy;
    std::vector<uint64_t> reported;
    train::LoopOptions options;
    options.iterations = 6;
    const train::LoopResult result =
        train::run_training_loop(trainer, strategy, cameras, views, photos, options,
                                 [&](const train::LoopStatus& s) { reported.push_back(s.iteration); });
    EXPECT_EQ(strategy.before, (std::vector<uint64_t>{1, 2, 3, 4, 5, 6}));
    EXPECT_EQ(strategy.after, strategy.before);
    EXPECT_EQ(result.iterations, 6u);
    EXPECT_FALSE(result.interrupted);
    ASSERT_FALSE(reported.empty());
    EXPECT_EQ(reported.back(), 6u);
    EXPECT_FALSE(result.stages.empty());
}

// A stop request ends the loop after the step in flight with a checkpoint; the run resumed from
// it takes the remaining steps only.
TEST_F(TrainingLoop, AStopCheckpointsAndAResumeTakesTheRest) {
    const fs::path checkpoint = fs::temp_directory_path() / "vksplat_training_loop.checkpoint";
    std::atomic<bool> stop{false};
    RecordingStrategy strategy;
    strategy.stop_after = 3;
    strategy.stop = &stop;
    train::LoopOptions options;
    options.iterations = 8;
    options.checkpoint = checkpoint;
    options.checkpoint_every = 100;
    options.stop = &stop;
    {
        train::Trainer trainer(context(), truth, {});
        const train::LoopResult result = train::run_training_loop(trainer, strategy, cameras, views, photos, options);
        EXPECT_TRUE(result.interrupted);
        EXPECT_EQ(result.iterations, 3u);
    }
    stop = false;
    train::Trainer resumed(context(), checkpoint, {});
    RecordingStrategy rest;
    EXPECT_EQ(train::run_training_loop(resumed, rest, cameras, views, photos, options).iterations, 8u);
    EXPECT_EQ(rest.before, (std::vector<uint64_t>{4, 5, 6, 7, 8}));
    fs::remove(checkpoint);
}

}  // namespace
}  // namespace vksplat::test
