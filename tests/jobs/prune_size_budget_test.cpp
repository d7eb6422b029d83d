// prune with a size budget (--max-mb): the file written fits, a larger budget keeps more, the
// re-fit reaches the choice in rounds and still fits, and what cannot be honoured is refused
// before any scoring.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <string>

#include "support/photos.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/jobs/prune_scene.hpp"
#include "vksplat/prune/sh_reduction.hpp"

namespace vksplat::test {
namespace {

namespace fs = std::filesystem;

class PruneSizeBudget : public PhotographedScene {
protected:
    PruneSizeBudget() : PhotographedScene("vksplat_prune_size_budget_") {}

    jobs::PruneOptions options(size_t max_bytes, const std::string& out) const {
        jobs::PruneOptions o;
        prune::SizeBudget budget;
        budget.max_bytes = max_bytes;
        o.selector = budget;
        o.out = dir / out;
        return o;
    }
    jobs::PruneResult prune(const jobs::PruneOptions& o) {
        scored = false;
        jobs::PruneProgress progress;
        progress.scoring = [this](size_t, size_t) { scored = true; };
        refit_rounds.clear();
        progress.refit = [this](int round, const train::LoopStatus&) { refit_rounds.insert(round); };
        return jobs::prune_scene(*renderer, cloud, cameras, o, progress);
    }
    std::string refusal(const jobs::PruneOptions& o) {
        try {
            prune(o);
        } catch (const InputError& e) {
            return e.what();
        }
        ADD_FAILURE() << "not refused";
        return {};
    }
    size_t whole_spz_bytes() const {
        io::write_scene(cloud, dir / "whole.spz");
        return fs::file_size(dir / "whole.spz");
    }
    bool scored = false;
    std::set<int> refit_rounds;  // the rounds progress.refit reported
};

TEST_F(PruneSizeBudget, WritesAFileThatFitsAndKeepsMoreForMore) {
    const size_t whole = whole_spz_bytes();
    const jobs::PruneResult small = prune(options(whole / 3, "small.spz"));
    EXPECT_LE(fs::file_size(dir / "small.spz"), whole / 3);
    EXPECT_EQ(small.bytes_after, fs::file_size(dir / "small.spz"));
    ASSERT_TRUE(small.budget);
    EXPECT_GT(small.budget->probes.size(), 1u) << "count traded against SH bands";
    EXPECT_EQ(small.count_after, small.budget->kept);

    const jobs::PruneResult larger = prune(options(whole * 2 / 3, "larger.spz"));
    EXPECT_LE(fs::file_size(dir / "larger.spz"), whole * 2 / 3);
    EXPECT_GT(fs::file_size(dir / "larger.spz"), fs::file_size(dir / "small.spz"));
    EXPECT_GT(larger.after.mean_psnr, small.after.mean_psnr);
    EXPECT_GE(larger.count_after, small.count_after);

    // The budget in another format is measured in that format.
    const jobs::PruneResult ply = prune(options(whole, "small.compressed.ply"));
    EXPECT_LE(fs::file_size(dir / "small.compressed.ply"), whole);
}

// The re-fit runs the rounds a plain --recover runs (RecoverOptions), down to the count chosen;
// then the share of bands chosen is dropped again and the file still fits.
TEST_F(PruneSizeBudget, ReachesTheChoiceInRoundsAndStillFits) {
    const size_t whole = whole_spz_bytes();
    jobs::PruneOptions o = options(whole / 2, "refit.spz");
    o.images_dir = dir / "photos";
    jobs::RecoverOptions recover;
    recover.iterations = 20;
    recover.rounds = 3;
    recover.round_spacing = 4;
    o.recover = recover;
    const jobs::PruneResult result = prune(o);
    EXPECT_LE(fs::file_size(dir / "refit.spz"), whole / 2);
    ASSERT_TRUE(result.budget);
    ASSERT_EQ(result.recover_rounds.size(), 3u);
    EXPECT_GT(result.recover_rounds[0].kept, result.recover_rounds[1].kept);
    EXPECT_GT(result.recover_rounds[1].kept, result.recover_rounds[2].kept);
    EXPECT_EQ(result.recover_rounds[2].kept, result.budget->kept) << "the last round keeps the count chosen";
    EXPECT_EQ(result.recover_rounds[0].iterations, 4u);
    EXPECT_EQ(result.recover_rounds[2].iterations, 12u);
    // The bands the choice dropped are dropped again after the re-fit (less those of Gaussians
    // dropped to fit again): the re-fit gives them colour that the file would pay for.
    const GaussianCloud written = io::read_scene(dir / "refit.spz");
    const prune::BudgetResult& chosen = *result.budget;
    ASSERT_GT(chosen.sh_share, 0.0) << "the test needs a choice that drops bands";
    EXPECT_LE(written.sh_degree, chosen.sh_degree);
    EXPECT_LE(written.size(), chosen.kept);
    long dropped = 0;
    for (uint8_t degree : prune::sh_degrees_in_use(written)) dropped += cloud.sh_degree - degree;
    const long gone = long(chosen.kept) - long(written.size());
    EXPECT_GE(dropped + gone * cloud.sh_degree, std::lround(chosen.sh_share * double(chosen.kept) * cloud.sh_degree));
}

// A long re-fit can grow the file past what its short re-fit foresaw: the Gaussians that then go
// are made up for by one more short re-fit of what is left, after which the file is fitted again.
TEST_F(PruneSizeBudget, GaussiansCutAfterTheReFitGetAShortReFitOfTheirOwn) {
    const size_t whole = whole_spz_bytes();
    jobs::PruneOptions o = options(whole / 2, "grown.spz");
    o.images_dir = dir / "photos";
    jobs::RecoverOptions recover;
    recover.iterations = 40;
    recover.rounds = 2;
    recover.round_spacing = 10;
    // A rate that throws the higher SH about: the re-fitted values fill far more bytes.
    recover.finetune.train.rates.sh_rest *= 400;
    o.recover = recover;
    const jobs::PruneResult result = prune(o);
    EXPECT_LE(fs::file_size(dir / "grown.spz"), whole / 2);
    ASSERT_TRUE(result.budget);
    ASSERT_EQ(result.recover_rounds.size(), 3u) << "two rounds and the short one after the cut";
    EXPECT_LT(result.recover_rounds[2].kept, result.recover_rounds[1].kept) << "Gaussians were cut after the re-fit";
    EXPECT_EQ(result.recover_rounds[2].iterations, 4u) << "a tenth of the re-fit's iterations";
    EXPECT_TRUE(result.recover_rounds[2].after_fit);
    EXPECT_FALSE(result.recover_rounds[1].after_fit);
    EXPECT_LE(result.count_after, result.recover_rounds[2].kept);
    // Progress names each re-fit: the shortlist's (0), the rounds' and the one after the fit.
    EXPECT_EQ(refit_rounds, (std::set<int>{jobs::kRefitAfterFit, 0, 1, 2}));
}

TEST_F(PruneSizeBudget, RefusesBeforeScoringWhatNoModelFitsAndAnOutputThatExists) {
    const std::string tiny = refusal(options(20, "tiny.spz"));
    EXPECT_NE(tiny.find("no model fits in it: the smallest, one Gaussian at SH degree 0, takes"), std::string::npos)
        << tiny;
    EXPECT_FALSE(scored);
    EXPECT_FALSE(fs::exists(dir / "tiny.spz"));

    io::write_scene(cloud, dir / "there.spz");
    const auto before = fs::file_size(dir / "there.spz");
    const std::string exists = refusal(options(whole_spz_bytes() / 2, "there.spz"));
    EXPECT_NE(exists.find("there.spz"), std::string::npos) << exists;
    EXPECT_FALSE(scored);
    EXPECT_EQ(fs::file_size(dir / "there.spz"), before);
}

}  // namespace
}  // namespace vksplat::test
