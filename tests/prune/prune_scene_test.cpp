// The prune job end to end: what it writes and reports, its refusals, saved scores, photos.
#include <gtest/gtest.h>


#include <filesystem>
#include <fstream>
#include <iterator>

#include "support/gpu_fixture.hpp"
#include "support/photos.hpp"
#include "support/scenes.hpp"
#include "support/scratch_dir.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/image.hpp"
#include "vksplat/io/ply.hpp"
#include "vksplat/jobs/prune_scene.hpp"
#include "vksplat/prune/score_files.hpp"

namespace vksplat::test {
namespace {

namespace fs = std::filesystem;

std::string read_bytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

class PruneScene : public GpuTest {
protected:
    void SetUp() override {
        dir = fresh_test_dir("vksplat_prune_scene_");
        renderer = std::make_unique<Renderer>(context());
        cloud = random_scene(71, 500, 2, 3.0f, 8.0f, 0.01f, 0.3f, 1.5f);
        cameras = row_of_five_views();
    }
    void TearDown() override {
        fs::remove_all(dir);
        GpuTest::TearDown();
    }
    jobs::PruneOptions options(jobs::PruneSelector selector, const std::string& out) const {
        jobs::PruneOptions o;
        o.selector = selector;
        o.out = dir / out;
        return o;
    }
    fs::path dir;
    std::unique_ptr<Renderer> renderer;
    GaussianCloud cloud;
    std::vector<Camera> cameras;
};

TEST(PruneViews, InriaConventionForTestAndTrainingViews) {
    const std::vector<size_t> first13 = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
    EXPECT_EQ(jobs::default_test_views(std::vector<Camera>(100)), first13);
    EXPECT_EQ(jobs::default_test_views(std::vector<Camera>(13)), first13) << "13 cameras: all are test views";
    EXPECT_EQ(jobs::default_test_views(std::vector<Camera>(3)), (std::vector<size_t>{0, 1, 2}));
    // Where every camera names its split, the split decides; where one does not, the convention.
    std::vector<Camera> split(20);
    for (size_t i = 0; i < split.size(); ++i) split[i].split = i % 5 == 2 ? "test" : "train";
    EXPECT_EQ(jobs::default_test_views(split), (std::vector<size_t>{2, 7, 12, 17}));
    split[19].split.clear();
    EXPECT_EQ(jobs::default_test_views(split), first13);
    EXPECT_EQ(jobs::default_train_views(15, first13), (std::vector<size_t>{13, 14}));
    EXPECT_EQ(jobs::default_train_views(3, {0, 1, 2}), (std::vector<size_t>{0, 1, 2})) << "none held out: all";
    EXPECT_EQ(jobs::default_train_views(4, {1, 3}), (std::vector<size_t>{0, 2}));
}

TEST_F(PruneScene, WritesThePrunedSceneAndReportsWhatItDid) {
    const jobs::PruneResult result = jobs::prune_scene(*renderer, cloud, cameras, options(jobs::DropRatio{0.5}, "half.ply"));
    EXPECT_EQ(result.count_before, 500u);
    EXPECT_EQ(result.count_after, 250u);
    EXPECT_TRUE(result.lossless_applied);
    EXPECT_EQ(result.test_views, (std::vector<size_t>{0, 1, 2, 3, 4}));
    EXPECT_EQ(result.train_views, result.test_views);
    EXPECT_GT(result.scoring_seconds, 0.0);
    EXPECT_FALSE(result.against_photos);
    EXPECT_FALSE(result.before);
    EXPECT_FALSE(result.budget);
    EXPECT_EQ(result.after.psnr.size(), 5u);
    EXPECT_GT(result.after.mean_psnr, 15.0);
    EXPECT_GT(result.after.mean_ssim, 0.5);

    const GaussianCloud written = io::read_ply(dir / "half.ply");
    EXPECT_EQ(written.size(), 250u);
    EXPECT_EQ(written.sh_degree, 2);
    EXPECT_EQ(result.bytes_before, cloud.ply_bytes());
    EXPECT_EQ(result.bytes_after, fs::file_size(dir / "half.ply"));
}

TEST_F(PruneScene, LosslessOnlyChangesNoPixelOfTheViewsUsed) {
    // Off-screen Gaussians added to the scene: --keep N (all) drops exactly those, losslessly.
    GaussianCloud with_extra = cloud;
    const GaussianCloud behind = random_scene(72, 60, 2, -6.0f, -1.0f);
    for (size_t i = 0; i < behind.size(); ++i) with_extra.append(behind, i);
    const jobs::PruneResult result =
        jobs::prune_scene(*renderer, with_extra, cameras, options(jobs::KeepCount{1000}, "lossless.ply"));
    EXPECT_GE(result.lossless_dropped, 60u);
    EXPECT_EQ(result.count_after, 560u - result.lossless_dropped);
    for (double psnr : result.after.psnr) EXPECT_TRUE(std::isinf(psnr)) << "bit-identical to the unpruned render";
    EXPECT_EQ(result.after.mean_ssim, 1.0);
}

TEST_F(PruneScene, RefusesExistingOutputsBeforeAnyWork) {
    std::ofstream(dir / "taken.ply") << "x";
    EXPECT_THROW(jobs::prune_scene(*renderer, cloud, cameras, options(jobs::KeepCount{10}, "taken.ply")), InputError);
    EXPECT_EQ(read_bytes(dir / "taken.ply"), "x");
    auto o = options(jobs::KeepCount{10}, "new.ply");
    o.save_scores = dir / "taken.ply";
    EXPECT_THROW(jobs::prune_scene(*renderer, cloud, cameras, o), InputError);
    EXPECT_FALSE(fs::exists(dir / "new.ply"));
    o.out = dir / "no_such_folder" / "x.ply";
    o.save_scores.reset();
    EXPECT_THROW(jobs::prune_scene(*renderer, cloud, cameras, o), InputError);
    o = options(jobs::KeepCount{10}, "taken.ply");
    o.mode = io::WriteMode::overwrite;
    EXPECT_NO_THROW(jobs::prune_scene(*renderer, cloud, cameras, o));
    EXPECT_EQ(io::read_ply(dir / "taken.ply").size(), 10u);
    EXPECT_THROW(jobs::prune_scene(*renderer, cloud, cameras, options(jobs::DropRatio{1.5}, "r.ply")), InputError);
    EXPECT_THROW(jobs::prune_scene(*renderer, cloud, cameras, options(jobs::KeepCount{1}, "")), InputError);
}

TEST_F(PruneScene, SavedTotalsAndScoresRedoTheSelectionWithoutRendering) {
    // 40 Gaussians behind the cameras give the lossless pass something to drop.
    const GaussianCloud behind = random_scene(74, 40, 2, -6.0f, -1.0f);
    for (size_t i = 0; i < behind.size(); ++i) cloud.append(behind, i);
    auto first = options(jobs::KeepCount{200}, "first.ply");
    first.save_scores = dir / "scores.npy";
    first.save_totals = dir / "totals.npy";
    const jobs::PruneResult r = jobs::prune_scene(*renderer, cloud, cameras, first);
    ASSERT_GE(r.lossless_dropped, 40u);
    ASSERT_LT(r.lossless_dropped, 150u);

    auto from_totals = options(jobs::KeepCount{200}, "from_totals.ply");
    from_totals.load_scores = dir / "totals.npy";
    const jobs::PruneResult t = jobs::prune_scene(*renderer, cloud, cameras, from_totals);
    EXPECT_TRUE(t.lossless_applied);
    EXPECT_EQ(t.scoring_seconds, 0.0);
    EXPECT_TRUE(read_bytes(dir / "from_totals.ply") == read_bytes(dir / "first.ply"));

    auto from_scores = options(jobs::KeepCount{200}, "from_scores.ply");
    from_scores.load_scores = dir / "scores.npy";
    const jobs::PruneResult s = jobs::prune_scene(*renderer, cloud, cameras, from_scores);
    EXPECT_FALSE(s.lossless_applied);
    EXPECT_EQ(s.count_after, 200u);
    EXPECT_TRUE(read_bytes(dir / "from_scores.ply") == read_bytes(dir / "first.ply"))
        << "blend is 0 wherever the lossless pass drops and these are fewer than the 340 dropped, so both "
           "ways drop them first";
    from_scores.out = dir / "again.ply";
    from_scores.save_totals = dir / "no_totals.npy";
    EXPECT_THROW(jobs::prune_scene(*renderer, cloud, cameras, from_scores), InputError) << "a scores file has none";

    // Totals let another method be scored; a scene of another size is refused.
    auto other = options(jobs::DropRatio{0.3}, "other.ply");
    other.method = prune::ScoreMethod::volume_blend;
    other.load_scores = dir / "totals.npy";
    other.save_scores = dir / "volume_blend.npy";
    EXPECT_EQ(jobs::prune_scene(*renderer, cloud, cameras, other).count_after, 378u);
    EXPECT_EQ(*prune::load_score_file(dir / "volume_blend.npy").scores,
              prune::score(cloud, *prune::load_score_file(dir / "totals.npy").totals, prune::ScoreMethod::volume_blend));
    other.save_scores.reset();
    other.out = dir / "other2.ply";
    EXPECT_THROW(jobs::prune_scene(*renderer, random_scene(73, 20, 2), cameras, other), InputError);
}

TEST_F(PruneScene, MeasuresAgainstPhotosAndWritesFewerShBands) {
    renderer->set_scene(cloud);
    write_renders_as_photos(*renderer, cameras, dir / "photos", 16);
    auto o = options(jobs::DropRatio{0.2}, "photos.ply");
    o.images_dir = dir / "photos";
    o.sh_degree = 1;
    const jobs::PruneResult result = jobs::prune_scene(*renderer, cloud, cameras, o);
    EXPECT_TRUE(result.against_photos);
    ASSERT_TRUE(result.before);
    EXPECT_GT(result.before->mean_psnr, 70.0) << "16-bit photos of the scene itself";
    EXPECT_GT(result.before->mean_ssim, 0.999);
    EXPECT_LT(result.after.mean_psnr, result.before->mean_psnr);
    EXPECT_EQ(result.sh_degree_before, 2);
    EXPECT_EQ(result.sh_degree_after, 1);
    EXPECT_EQ(io::read_ply(dir / "photos.ply").sh_degree, 1);
    EXPECT_EQ(result.bytes_after, fs::file_size(dir / "photos.ply"));

    fs::remove(dir / "photos" / "view_3.png");
    o.out = dir / "missing.ply";
    EXPECT_THROW(jobs::prune_scene(*renderer, cloud, cameras, o), InputError);
}

TEST_F(PruneScene, QualityBudgetReportsItsProbes) {
    prune::QualityBudget budget;
    budget.max_psnr_drop = 1.0;
    size_t heard = 0;
    jobs::PruneProgress progress;
    progress.probe = [&](const prune::BudgetProbe&) { ++heard; };
    auto o = options(budget, "budget.ply");
    o.test_views = {0, 4};
    o.train_views = {1, 2, 3};
    const jobs::PruneResult result = jobs::prune_scene(*renderer, cloud, cameras, o, progress);
    ASSERT_TRUE(result.budget);
    EXPECT_EQ(heard, result.budget->probes.size());
    EXPECT_GT(heard, 3u);
    EXPECT_EQ(result.count_after, result.budget->kept);
    EXPECT_LT(result.count_after, result.count_before);
    EXPECT_EQ(result.after.psnr.size(), 2u);
}

}  // namespace
}  // namespace vksplat::test
