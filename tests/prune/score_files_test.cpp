// Scores and view totals saved as .npy and loaded back.
#include <gtest/gtest.h>

#include <filesystem>

#include "support/scratch_dir.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/npy.hpp"
#include "vksplat/prune/score_files.hpp"

namespace vksplat::test {
namespace {

namespace fs = std::filesystem;

class ScoreFiles : public ::testing::Test {
protected:
    void SetUp() override { dir = fresh_test_dir("vksplat_score_files_"); }
    void TearDown() override { fs::remove_all(dir); }
    fs::path dir;
};

TEST_F(ScoreFiles, ScoresRoundTripAsFloat32Vectors) {
    const std::vector<float> scores = {0.5f, -1.0f, 3e7f, 0.0f};
    prune::save_scores(scores, dir / "s.npy");
    const io::NpyArray array = io::read_npy(dir / "s.npy");
    EXPECT_EQ(array.shape, (std::vector<size_t>{4}));
    EXPECT_EQ(array.dtype, io::NpyDtype::float32);
    const prune::ScoreFile file = prune::load_score_file(dir / "s.npy");
    ASSERT_TRUE(file.scores);
    EXPECT_FALSE(file.totals);
    EXPECT_EQ(*file.scores, scores);
    EXPECT_EQ(file.size(), 4u);
    EXPECT_THROW(prune::save_scores(scores, dir / "s.npy"), InputError) << "never overwrites unasked";
    EXPECT_NO_THROW(prune::save_scores(scores, dir / "s.npy", io::WriteMode::overwrite));
}

TEST_F(ScoreFiles, TotalsRoundTripAsFiveColumns) {
    prune::ViewTotals totals(3);
    totals.blend = {1.5, 0.0, 123.25};
    totals.blend_max = {0.5f, 0.0f, 0.99f};
    totals.pixels = {7, 0, 16777216};
    totals.footprint = {3.0, 0.0, 1e6};
    totals.views_visible = {1, 0, 12};
    totals.views = 12;
    prune::save_totals(totals, dir / "t.npy");
    EXPECT_EQ(io::read_npy(dir / "t.npy").shape, (std::vector<size_t>{3, 5}));
    const prune::ScoreFile file = prune::load_score_file(dir / "t.npy");
    ASSERT_TRUE(file.totals);
    EXPECT_FALSE(file.scores);
    EXPECT_EQ(file.totals->blend, totals.blend);
    EXPECT_EQ(file.totals->blend_max, totals.blend_max);
    EXPECT_EQ(file.totals->pixels, totals.pixels);
    EXPECT_EQ(file.totals->footprint, totals.footprint);
    EXPECT_EQ(file.totals->views_visible, totals.views_visible);
}

TEST_F(ScoreFiles, TotalsWithFisherRoundTripAsSixColumns) {
    prune::ViewTotals totals(2);
    totals.blend = {1.5, 0.0};
    totals.pixels = {7, 0};
    totals.fisher = {12.25f, -165.75f};
    prune::save_totals(totals, dir / "f.npy");
    EXPECT_EQ(io::read_npy(dir / "f.npy").shape, (std::vector<size_t>{2, 6}));
    const prune::ScoreFile file = prune::load_score_file(dir / "f.npy");
    ASSERT_TRUE(file.totals);
    EXPECT_EQ(file.totals->fisher, totals.fisher);
    EXPECT_EQ(file.totals->blend, totals.blend);
    EXPECT_EQ(file.totals->pixels, totals.pixels);
    totals.fisher.clear();
    prune::save_totals(totals, dir / "plain.npy");
    EXPECT_TRUE(prune::load_score_file(dir / "plain.npy").totals->fisher.empty());
}

TEST_F(ScoreFiles, OtherShapesAndTypesAreRefusedByName) {
    const float grid[6] = {1, 2, 3, 4, 5, 6};
    io::write_npy(dir / "grid.npy", grid, {2, 3});
    try {
        prune::load_score_file(dir / "grid.npy");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("grid.npy: has shape [2, 3]; expected scores [N] or view totals [N, 5]"),
                  std::string::npos)
            << e.what();
    }
    const int32_t ints[2] = {1, 2};
    io::write_npy(dir / "ints.npy", ints, {2});
    EXPECT_THROW(prune::load_score_file(dir / "ints.npy"), InputError);
}

}  // namespace
}  // namespace vksplat::test
