// Selectors: threshold, ratio and count, their edge cases and ties, and how they sit on top of the
// lossless pass.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
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

// Ranked by sampling_keys, the kept are a weighted sample without replacement: each Gaussian's
// chance of being the first drawn is its share of the scores. Checked by counting over many seeds,
// against the exact probabilities, for a first draw and for keeping two of four.
TEST(Selection, SamplingKeysDrawInProportionToTheScores) {
    const std::vector<float> scores{1.0f, 2.0f, 3.0f, 4.0f};
    const std::vector<uint8_t> all(scores.size(), 1);
    constexpr int kSeeds = 20000;
    std::array<int, 4> first{}, kept_two{};
    for (int seed = 0; seed < kSeeds; ++seed) {
        const prune::Ranking ranking(prune::sampling_keys(scores, uint64_t(seed)), all);
        const auto one = ranking.keep_best(1);
        const auto two = ranking.keep_best(2);
        for (size_t i = 0; i < 4; ++i) {
            first[i] += one[i];
            kept_two[i] += two[i];
        }
    }
    // P(i kept of two) = p_i + sum_{j != i} p_j p_i / (1 - p_j), p = score / 10.
    std::array<double, 4> two_exact{};
    for (size_t i = 0; i < 4; ++i) {
        const double pi = scores[i] / 10.0;
        two_exact[i] = pi;
        for (size_t j = 0; j < 4; ++j)
            if (j != i) two_exact[i] += (scores[j] / 10.0) * pi / (1.0 - scores[j] / 10.0);
    }
    for (size_t i = 0; i < 4; ++i) {
        // 4.5 standard deviations of a binomial count.
        const double p1 = scores[i] / 10.0;
        EXPECT_NEAR(first[i] / double(kSeeds), p1, 4.5 * std::sqrt(p1 * (1 - p1) / kSeeds)) << i;
        const double p2 = two_exact[i];
        EXPECT_NEAR(kept_two[i] / double(kSeeds), p2, 4.5 * std::sqrt(p2 * (1 - p2) / kSeeds)) << i;
    }
}

// A score of 0 or below is never drawn before a positive one, NaN never before those, and the
// same seed gives the same keys (a resumed or repeated run keeps the same Gaussians).
TEST(Selection, SamplingKeysRankNonPositiveAndNanLastAndRepeat) {
    const std::vector<float> scores{0.0f, std::nanf(""), 1e-30f, -1.0f, 5.0f};
    const auto keys = prune::sampling_keys(scores, 7);
    const auto same = prune::sampling_keys(scores, 7), other = prune::sampling_keys(scores, 8);
    ASSERT_EQ(same.size(), keys.size());
    EXPECT_EQ(std::memcmp(same.data(), keys.data(), keys.size() * sizeof(float)), 0);  // NaN too, bit for bit
    EXPECT_NE(other[4], keys[4]);
    EXPECT_TRUE(std::isnan(keys[1]));
    const prune::Ranking ranking(keys, std::vector<uint8_t>(scores.size(), 1));
    EXPECT_EQ(ranking.keep_best(2), (prune::KeepMask{0, 0, 1, 0, 1}));
    EXPECT_EQ(ranking.keep_best(4), (prune::KeepMask{1, 0, 1, 1, 1}));
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
