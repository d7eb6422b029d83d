// Selectors: threshold, ratio and count, their edge cases and ties, and how they sit on top of the
// lossless pass.
#include <gtest/gtest.h>

#include <limits>

#include "vksplat/error.hpp"
#include "vksplat/prune/selection.hpp"

namespace vksplat::test {
namespace {

using prune::KeepMask;

const std::vector<float> kScores = {0.5f, 0.1f, 0.9f, 0.3f, 0.7f};  // best first: 2, 4, 0, 3, 1
const KeepMask kAll = prune::keep_all(5);

TEST(Selection, ThresholdDropsScoresAtOrBelowIt) {
    EXPECT_EQ(prune::select_threshold(kScores, 0.3f, kAll), (KeepMask{1, 0, 1, 0, 1}));
    EXPECT_EQ(prune::select_threshold(kScores, 0.0f, kAll), kAll);
    EXPECT_EQ(prune::select_threshold(kScores, 0.9f, kAll), KeepMask(5, 0));
    EXPECT_EQ(prune::select_threshold(kScores, 0.0f, KeepMask{1, 1, 0, 1, 1}), (KeepMask{1, 1, 0, 1, 1}))
        << "what the lossless pass dropped stays dropped";
}

TEST(Selection, CountKeepsTheBest) {
    EXPECT_EQ(prune::select_count(kScores, 2, kAll), (KeepMask{0, 0, 1, 0, 1}));
    EXPECT_EQ(prune::select_count(kScores, 0, kAll), KeepMask(5, 0));
    EXPECT_EQ(prune::select_count(kScores, 5, kAll), kAll);
    EXPECT_EQ(prune::select_count(kScores, 99, kAll), kAll) << "keep > N keeps everything";
}

TEST(Selection, RatioDropsTheLowestFractionOfTheOriginalCount) {
    EXPECT_EQ(prune::select_ratio(kScores, 0.0, kAll), kAll);
    EXPECT_EQ(prune::select_ratio(kScores, 1.0, kAll), KeepMask(5, 0));
    EXPECT_EQ(prune::select_ratio(kScores, 0.4, kAll), (KeepMask{1, 0, 1, 0, 1}));
    EXPECT_EQ(prune::select_ratio(kScores, 0.5, kAll), (KeepMask{0, 0, 1, 0, 1})) << "round(2.5) = 3 dropped";
    EXPECT_THROW(prune::select_ratio(kScores, -0.1, kAll), InputError);
    EXPECT_THROW(prune::select_ratio(kScores, 1.5, kAll), InputError);
    EXPECT_THROW(prune::select_ratio(kScores, std::numeric_limits<double>::quiet_NaN(), kAll), InputError);
}

TEST(Selection, LosslessPassComesFirstAndCountsTowardTheRatio) {
    // The lossless pass dropped the best-scoring one (2): the ratio still counts against N = 5.
    const KeepMask lossless = {1, 1, 0, 1, 1};
    EXPECT_EQ(prune::select_ratio(kScores, 0.2, lossless), lossless) << "asked 1 dropped, lossless dropped 1";
    EXPECT_EQ(prune::select_ratio(kScores, 0.4, lossless), (KeepMask{1, 0, 0, 1, 1}));
    EXPECT_EQ(prune::select_ratio(kScores, 0.0, lossless), lossless) << "lossless drops more than asked: only it";
    EXPECT_EQ(prune::select_count(kScores, 4, lossless), lossless);
    EXPECT_EQ(prune::select_count(kScores, 1, lossless), (KeepMask{0, 0, 0, 0, 1}));
}

TEST(Selection, TiesGoByIndexAndNanRanksLast) {
    const std::vector<float> tied = {0.5f, 0.5f, 0.5f, 0.5f};
    EXPECT_EQ(prune::select_count(tied, 2, prune::keep_all(4)), (KeepMask{1, 1, 0, 0})) << "lower index kept first";
    EXPECT_EQ(prune::select_count(tied, 3, KeepMask{0, 1, 1, 1}), (KeepMask{0, 1, 1, 1}));
    EXPECT_EQ(prune::select_count(tied, 1, KeepMask{0, 1, 1, 1}), (KeepMask{0, 1, 0, 0}));
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::vector<float> with_nan = {nan, -1.0f, nan, 2.0f};
    EXPECT_EQ(prune::select_count(with_nan, 2, prune::keep_all(4)), (KeepMask{0, 1, 0, 1}));
    EXPECT_EQ(prune::select_count(with_nan, 3, prune::keep_all(4)), (KeepMask{1, 1, 0, 1}));
}

TEST(Selection, RankingGivesTheBestOfAnyCount) {
    const prune::Ranking ranking(kScores, KeepMask{1, 1, 1, 0, 1});
    EXPECT_EQ(ranking.size(), 5u);
    EXPECT_EQ(ranking.candidates(), 4u);
    EXPECT_EQ(ranking.keep_best(0), KeepMask(5, 0));
    EXPECT_EQ(ranking.keep_best(1), (KeepMask{0, 0, 1, 0, 0}));
    EXPECT_EQ(ranking.keep_best(3), (KeepMask{1, 0, 1, 0, 1}));
    EXPECT_EQ(ranking.keep_best(10), (KeepMask{1, 1, 1, 0, 1}));
    EXPECT_EQ(prune::count_kept(ranking.keep_best(3)), 3u);
    EXPECT_THROW(prune::Ranking(kScores, prune::keep_all(4)), std::invalid_argument);
}

TEST(Selection, EmptyScene) {
    EXPECT_TRUE(prune::select_ratio({}, 0.5, {}).empty());
    EXPECT_TRUE(prune::select_count({}, 3, {}).empty());
    EXPECT_TRUE(prune::select_threshold({}, 0.0f, {}).empty());
}

TEST(Selection, LosslessMaskReadsThePixelCounts) {
    prune::ViewTotals totals(3);
    totals.pixels = {0, 1, 12};
    totals.blend = {0.5, 0.0, 1.0};  // a blend weight below 1/255 per pixel does not count
    EXPECT_EQ(prune::lossless_mask(totals), (KeepMask{0, 1, 1}));
}

}  // namespace
}  // namespace vksplat::test
