// prune --recover checks its photos and options before it scores the training views, which takes
// minutes on a real scene: a missing photo found after the scoring would waste them.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "support/gpu_fixture.hpp"
#include "support/photos.hpp"
#include "support/scenes.hpp"
#include "support/scratch_dir.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/image.hpp"
#include "vksplat/jobs/prune_recover.hpp"
#include "vksplat/jobs/prune_scene.hpp"

namespace vksplat::test {
namespace {

namespace fs = std::filesystem;

class RecoverChecks : public PhotographedScene {
protected:
    RecoverChecks() : PhotographedScene("vksplat_recover_checks_") {}

    // Views 0 and 1 held out: the photos of 2-4 are read by the re-fit alone.
    jobs::PruneOptions recover_options() const {
        jobs::PruneOptions o;
        o.selector = jobs::DropRatio{0.5};
        o.out = dir / "out.ply";
        o.images_dir = dir / "photos";
        o.test_views = {0, 1};
        jobs::RecoverOptions recover;
        recover.iterations = 6;
        recover.rounds = 1;
        o.recover = recover;
        return o;
    }
    // Runs the job and returns its refusal's message; records whether it started scoring.
    std::string refusal(const jobs::PruneOptions& options) {
        scored = false;
        jobs::PruneProgress progress;
        progress.scoring = [this](size_t, size_t) { scored = true; };
        try {
            jobs::prune_scene(*renderer, cloud, cameras, options, progress);
        } catch (const InputError& e) {
            return e.what();
        }
        ADD_FAILURE() << "not refused";
        return {};
    }
    bool scored = false;
};

TEST_F(RecoverChecks, TrainingPhotosBeforeScoring) {
    const std::vector<float> grey(32 * 32 * 3, 0.5f);
    io::write_png_rgb(dir / "photos" / "view_3.png", 32, 32, grey.data(), 8, io::WriteMode::overwrite);
    const std::string wrong_size = refusal(recover_options());
    EXPECT_NE(wrong_size.find("view_3"), std::string::npos) << wrong_size;
    EXPECT_NE(wrong_size.find("32x32"), std::string::npos) << wrong_size;
    EXPECT_FALSE(scored) << "refused only after scoring";

    fs::remove(dir / "photos" / "view_3.png");
    const std::string missing = refusal(recover_options());
    EXPECT_NE(missing.find("view_3"), std::string::npos) << missing;
    EXPECT_FALSE(scored) << "refused only after scoring";
}

TEST_F(RecoverChecks, OptionsBeforeScoring) {
    auto too_few = recover_options();
    too_few.recover->iterations = 2;
    too_few.recover->rounds = 3;
    const std::string rounds = refusal(too_few);
    EXPECT_NE(rounds.find("--recover 2"), std::string::npos) << rounds;
    EXPECT_FALSE(scored) << "refused only after scoring";

    auto budget = recover_options();
    budget.selector = prune::QualityBudget{};
    budget.recover->rounds = 3;
    const std::string budget_rounds = refusal(budget);
    EXPECT_NE(budget_rounds.find("--rounds 3"), std::string::npos) << budget_rounds;
    EXPECT_FALSE(scored) << "refused only after scoring";
}

// --recover N re-fits N iterations in all, however many rounds share them (50 over 3 rounds was
// 3 x 16 = 48).
TEST(RoundIterations, AddUpToTheIterationsAskedFor) {
    EXPECT_EQ(jobs::round_iterations(50, 1, 3), 17u);
    EXPECT_EQ(jobs::round_iterations(50, 2, 3), 17u);
    EXPECT_EQ(jobs::round_iterations(50, 3, 3), 16u);
    for (const auto& [iterations, rounds] : {std::pair<uint64_t, int>{5000, 3}, {7, 7}, {10, 1}, {101, 4}}) {
        uint64_t sum = 0;
        for (int round = 1; round <= rounds; ++round) sum += jobs::round_iterations(iterations, round, rounds);
        EXPECT_EQ(sum, iterations) << iterations << " over " << rounds;
    }
}

// With a spacing, the rounds before the last take it and the last the rest, still adding up, and
// a run too short for the spacing still gives every round a step.
TEST(RoundIterations, SpacedRoundsLeaveTheRestToTheLast) {
    EXPECT_EQ(jobs::round_iterations(30000, 1, 3, 1000), 1000u);
    EXPECT_EQ(jobs::round_iterations(30000, 2, 3, 1000), 1000u);
    EXPECT_EQ(jobs::round_iterations(30000, 3, 3, 1000), 28000u);
    EXPECT_EQ(jobs::round_iterations(30000, 1, 1, 1000), 30000u);
    for (const auto& [iterations, rounds] : {std::pair<uint64_t, int>{5000, 3}, {7, 7}, {10, 1}, {101, 4}, {2500, 3}}) {
        uint64_t sum = 0;
        for (int round = 1; round <= rounds; ++round) {
            const uint64_t steps = jobs::round_iterations(iterations, round, rounds, 1000);
            EXPECT_GE(steps, 1u) << iterations << " over " << rounds << ", round " << round;
            sum += steps;
        }
        EXPECT_EQ(sum, iterations) << iterations << " over " << rounds;
    }
}

// Unset, the rounds are five but one per spacing where the re-fit is shorter, so the kept model
// re-fits at least the spacing; asked for, they are what was asked.
TEST(RecoverRounds, AShortReFitRunsFewerRoundsUnlessAskedFor) {
    jobs::RecoverOptions options;
    EXPECT_EQ(jobs::recover_rounds(options, 50000), jobs::kDefaultRecoverRounds);
    EXPECT_EQ(jobs::recover_rounds(options, 5000), 5);
    EXPECT_EQ(jobs::recover_rounds(options, 4999), 4);
    EXPECT_EQ(jobs::recover_rounds(options, 2500), 2);
    EXPECT_EQ(jobs::recover_rounds(options, 300), 1);
    EXPECT_EQ(jobs::recover_rounds(options, 0), 1);
    options.round_spacing = 500;
    EXPECT_EQ(jobs::recover_rounds(options, 1500), 3);
    options.round_spacing = 0;  // equal shares: still at least 1,000 steps a round
    EXPECT_EQ(jobs::recover_rounds(options, 3000), 3);
    for (uint64_t iterations : {1000, 2000, 3999, 5000, 60000}) {
        const int rounds = jobs::recover_rounds(jobs::RecoverOptions(), iterations);
        EXPECT_GE(jobs::round_iterations(iterations, rounds, rounds, 1000), 1000u) << iterations;
    }
    options.rounds = 4;
    EXPECT_EQ(jobs::recover_rounds(options, 300), 4);
    jobs::RecoverOptions timed;
    timed.seconds = 1;
    EXPECT_EQ(jobs::recover_rounds(timed, 0), jobs::kDefaultRecoverRounds) << "a time budget's steps are not known";
}

TEST_F(RecoverChecks, AShortReFitWithTheDefaultRoundsRunsOne) {
    auto options = recover_options();
    options.recover->iterations = 7;
    options.recover->rounds.reset();
    const jobs::PruneResult result = jobs::prune_scene(*renderer, cloud, cameras, options);
    ASSERT_EQ(result.recover_rounds.size(), 1u);
    EXPECT_EQ(result.recover_rounds[0].iterations, 7u);
}

// A caller's own photo source (PruneOptions::photos) stands for the folder: the re-fit reads it
// and quality is measured against it, with no images_dir at all.
TEST_F(RecoverChecks, PhotosFromTheCallersSourceServeAsTheFolder) {
    auto from_folder = recover_options();
    from_folder.out = dir / "from_folder.ply";
    const jobs::PruneResult expected = jobs::prune_scene(*renderer, cloud, cameras, from_folder);
    auto from_source = recover_options();
    from_source.out = dir / "from_source.ply";
    from_source.images_dir.reset();
    size_t reads = 0;
    const jobs::PhotoSource folder = jobs::photos_in_folder(dir / "photos", from_source.settings.background);
    from_source.photos = [&](const Camera& camera) {
        ++reads;
        return folder(camera);
    };
    const jobs::PruneResult result = jobs::prune_scene(*renderer, cloud, cameras, from_source);
    EXPECT_TRUE(result.against_photos);
    ASSERT_TRUE(result.before.has_value());
    EXPECT_EQ(result.before->mean_psnr, expected.before->mean_psnr) << "the same photos, the same unpruned scene";
    EXPECT_EQ(result.count_after, expected.count_after);
    EXPECT_GE(reads, cameras.size()) << "the test views' targets and the re-fit's views";
}

TEST_F(RecoverChecks, TheRoundsTakeExactlyTheIterationsAskedFor) {
    auto options = recover_options();
    options.recover->iterations = 7;
    options.recover->rounds = 2;
    uint64_t steps = 0;
    jobs::PruneProgress progress;
    progress.refit = [&](int, const train::LoopStatus& s) {
        if (s.iteration == s.iterations) steps += s.iterations;
    };
    jobs::prune_scene(*renderer, cloud, cameras, options, progress);
    EXPECT_EQ(steps, 7u);
}

// A time budget chooses the rounds' iterations: the result says how many each took, and in what time.
TEST_F(RecoverChecks, EachRoundSaysWhatItsReFitTook) {
    auto options = recover_options();
    options.recover->iterations.reset();
    options.recover->seconds = 2;
    options.recover->rounds = 2;
    const jobs::PruneResult result = jobs::prune_scene(*renderer, cloud, cameras, options);
    ASSERT_EQ(result.recover_rounds.size(), 2u);
    EXPECT_GT(result.recover_rounds[0].kept, result.recover_rounds[1].kept);
    double seconds = 0;
    for (const auto& round : result.recover_rounds) {
        EXPECT_GE(round.iterations, 1u);
        EXPECT_GT(round.seconds, 0.0);
        seconds += round.seconds;
    }
    EXPECT_LT(seconds, 10.0) << "the rounds' steps overran a 2 s budget";
}

}  // namespace
}  // namespace vksplat::test
