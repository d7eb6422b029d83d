// Cluster pruning end to end on a generated scene whose subject and clutter are known: a ball of
// small Gaussians (red lower half, blue upper half) and faint floaters around it, seen by an orbit of cameras.
#include <gtest/gtest.h>


#include <cmath>
#include <filesystem>
#include <random>

#include "support/gpu_fixture.hpp"
#include "support/scenes.hpp"
#include "support/scratch_dir.hpp"
#include "vksplat/scene/demo_scene.hpp"
#include "vksplat/io/npy.hpp"
#include "vksplat/io/ply.hpp"
#include "vksplat/jobs/cluster_work_dir.hpp"

namespace vksplat::test {
namespace {

namespace fs = std::filesystem;

constexpr size_t kSubject = 2000;
constexpr size_t kFloaters = 60;

// Gaussians 0..kSubject-1 are the ball (z < 0 red, z >= 0 blue: every orbit camera sees both
// halves), the rest floaters.
void add_ball(GaussianCloud& cloud, std::mt19937& random) {
    std::normal_distribution<double> normal;
    for (size_t i = 0; i < kSubject; ++i) {
        glm::dvec3 p{normal(random), normal(random), normal(random)};
        p *= 0.6 / glm::length(p);  // on the sphere of radius 0.6
        const glm::dvec3 colour = p.z < 0 ? glm::dvec3{0.9, 0.1, 0.1} : glm::dvec3{0.1, 0.2, 0.9};
        add_splat(cloud, {.position = p, .scale = {0.03, 0.03, 0.03}, .opacity = 0.95, .color = colour});
    }
}

GaussianCloud ball_and_floaters() {
    GaussianCloud cloud;
    cloud.sh_degree = 0;
    std::mt19937 random(3);
    add_ball(cloud, random);
    std::uniform_real_distribution<double> angle(0.0, 6.283), height(-1.0, 1.0), radius(1.6, 2.4);
    for (size_t i = 0; i < kFloaters; ++i) {
        const double a = angle(random), r = radius(random);
        add_splat(cloud, {.position = {r * std::cos(a), r * std::sin(a), height(random)},
                          .scale = {0.15, 0.15, 0.15},
                          .opacity = 0.08,
                          .color = {0.7, 0.7, 0.7}});
    }
    return cloud;
}

// The ball inside a room: kRoom wide opaque splats on a sphere of radius 9, outside the cameras'
// orbit (radius 4), so every picture has the room behind the ball.
constexpr size_t kRoom = 300;
GaussianCloud ball_in_room() {
    GaussianCloud cloud;
    cloud.sh_degree = 0;
    std::mt19937 random(5);
    add_ball(cloud, random);
    std::normal_distribution<double> normal;
    for (size_t i = 0; i < kRoom; ++i) {
        glm::dvec3 p{normal(random), normal(random), normal(random)};
        p *= 9.0 / glm::length(p);
        add_splat(cloud, {.position = p, .scale = {0.8, 0.8, 0.8}, .opacity = 0.9, .color = {0.6, 0.55, 0.5}});
    }
    return cloud;
}

class ClusterPrune : public GpuTest {
protected:
    void SetUp() override {
        dir = fresh_test_dir("vksplat_cluster_");
        options.max_views = 8;
        options.resolution_scale = 1.0;
        options.delta = 0.2;
        // Small pictures: a finer scale than the default, made for pictures of a few hundred pixels.
        options.segmentation.k = 150;
        log = [this](const std::string& line) { lines += line + "\n"; };
    }
    void TearDown() override {
        fs::remove_all(dir);
        GpuTest::TearDown();
    }
    fs::path dir;
    GaussianCloud cloud = ball_and_floaters();
    std::vector<Camera> cameras = make_orbit_cameras(8, 128, 96, 4.0, 20.0);
    jobs::ClusterOptions options;
    std::string lines;
    jobs::Log log;
};

// The G* drops the faint floaters first: they sit in few regions of few views. The default
// G* weighs what each cluster paints, and a floater, faint but five times wider, paints more than
// one of the ball's small splats: floaters stay, and the ball loses a few splats for them.
TEST_F(ClusterPrune, KeepsTheSubjectAndDropsTheFloatersFirst) {
    Renderer renderer(context());
    const auto kept = [&](const jobs::ClusterOptions& o) {
        const auto keep = jobs::cluster_keep_mask(renderer, context(), cloud, cameras, kSubject, o, log);
        EXPECT_EQ(keep.size(), cloud.size());
        std::pair<size_t, size_t> counts{0, 0};  // subject, floaters
        for (size_t i = 0; i < keep.size(); ++i) (i < kSubject ? counts.first : counts.second) += keep[i];
        EXPECT_EQ(counts.first + counts.second, kSubject);
        return counts;
    };
    jobs::ClusterOptions original = options;
    original.weights = cluster::kOriginalWeights;
    EXPECT_LE(kept(original).second, kFloaters / 10) << lines;
    EXPECT_NE(lines.find("views: kept"), std::string::npos) << lines;
    EXPECT_GE(kept(options).first, kSubject - kFloaters) << lines;
}

// Centrality finds the subject without segmentation or hand-picked views: every camera looks at
// the ball, and each piece of the room is in the middle of one picture at most. By contribution
// alone the room, which fills every picture, outranks the ball's small splats.
TEST_F(ClusterPrune, CentralityKeepsTheSubjectAndDropsTheRoom) {
    Renderer renderer(context());
    const GaussianCloud room = ball_in_room();
    const auto kept_room = [&](const jobs::ClusterOptions& o) {
        const auto keep = jobs::cluster_keep_mask(renderer, context(), room, cameras, kSubject, o, log);
        size_t count = 0;
        for (size_t i = kSubject; i < keep.size(); ++i) count += keep[i];
        return count;
    };
    jobs::ClusterOptions central = options;
    central.weights.lambda = 1.0;
    EXPECT_EQ(kept_room(central), 0u) << lines;
    EXPECT_NE(lines.find("central (centrality >= 0.25): 2000 of 2300"), std::string::npos) << lines;
    EXPECT_GT(kept_room(options), kRoom / 2) << lines;
}

TEST_F(ClusterPrune, StagesThroughAWorkFolderAndRerunFromSavedOutputs) {
    Renderer renderer(context());
    jobs::ClusterStageIo io{dir, io::WriteMode::refuse_existing, log, {}};
    jobs::regions_stage(renderer, cloud, cameras, options, std::nullopt, io);
    EXPECT_TRUE(fs::exists(dir / "regions" / "view_0000.npy"));
    EXPECT_TRUE(fs::exists(dir / "regions" / "view_0007.png"));
    jobs::project_stage(renderer, context(), cloud, cameras, options, io);
    const io::NpyArray projection = io::read_npy(dir / "projection.npy");
    EXPECT_EQ(projection.shape[1], cloud.size());
    const cluster::Clustering clustering = jobs::build_stage(cloud, options, io);
    // The semantic constraint keeps the ball's halves apart: no cluster of several Gaussians
    // spans both colours.
    std::map<int32_t, std::pair<size_t, size_t>> halves;  // cluster -> (red, blue) members
    for (size_t i = 0; i < kSubject; ++i)
        (cloud.positions[i * 3 + 2] < 0 ? halves[clustering.cluster_of[i]].first : halves[clustering.cluster_of[i]].second)++;
    size_t mixed = 0;
    for (const auto& [id, counts] : halves) mixed += std::min(counts.first, counts.second);
    EXPECT_LT(mixed, kSubject / 20) << lines;
    EXPECT_LT(clustering.summary.clusters, kSubject / 2) << lines;

    const cluster::ClusterScores first = jobs::score_stage(cloud, cameras, options, io);
    EXPECT_NE(lines.find("percentile"), std::string::npos);
    // A stage's output is not replaced unasked; with overwrite, new weights give new scores.
    EXPECT_THROW(jobs::score_stage(cloud, cameras, options, io), InputError);
    io.mode = io::WriteMode::overwrite;
    options.weights = cluster::kOriginalWeights;
    const cluster::ClusterScores second = jobs::score_stage(cloud, cameras, options, io);
    EXPECT_EQ(first.size(), second.size());
    EXPECT_NE(first.score, second.score);
    EXPECT_EQ(io::read_npy(dir / "cluster_scores.npy").shape, (std::vector<size_t>{second.size(), 9}));
    options.weights = {};
    jobs::score_stage(cloud, cameras, options, io);

    options.selection.ratio = 0.5;
    const auto result = jobs::prune_stage(cloud, options, dir / "out.ply", io);
    EXPECT_EQ(result.count_before, cloud.size());
    EXPECT_GT(result.count_after, 0u);
    EXPECT_LT(result.count_after, cloud.size());
    EXPECT_EQ(io::read_ply(dir / "out.ply").size(), result.count_after);
    // A later stage without its inputs says which stage to run.
    fs::remove(dir / "clusters.npy");
    try {
        jobs::score_stage(cloud, cameras, options, io);
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("vksplat cluster build"), std::string::npos) << e.what();
    }
}

// The quality budget holds on the test views whatever the cluster scores are worth: the model it
// writes is measured again here, and a looser budget keeps fewer Gaussians.
TEST_F(ClusterPrune, AQualityBudgetHoldsOnTheTestViews) {
    Renderer renderer(context());
    jobs::ClusterStageIo io{dir, io::WriteMode::refuse_existing, log, {}};
    jobs::regions_stage(renderer, cloud, cameras, options, std::nullopt, io);
    jobs::project_stage(renderer, context(), cloud, cameras, options, io);
    jobs::build_stage(cloud, options, io);
    jobs::score_stage(cloud, cameras, options, io);
    const std::vector<Camera> test(cameras.begin(), cameras.begin() + 3);
    RenderSettings settings;
    const eval::TestViews targets = eval::render_targets(renderer, cloud, test, settings);

    std::vector<size_t> kept;
    for (double budget : {0.05, 1.0}) {
        const fs::path out = dir / ("budget_" + std::to_string(budget) + ".ply");
        size_t probes = 0;
        prune::QualityBudget asked;
        asked.max_psnr_drop = budget;
        const auto result = jobs::prune_stage_to_budget(renderer, cloud, targets, asked, settings, out, io,
                                                        [&](const prune::BudgetProbe&) { ++probes; });
        ASSERT_TRUE(result.budget);
        EXPECT_TRUE(result.budget->met);
        EXPECT_EQ(probes, result.budget->probes.size());
        EXPECT_LE(result.budget->drop, budget);
        const GaussianCloud written = io::read_ply(out);
        EXPECT_EQ(written.size(), result.count_after);
        EXPECT_EQ(result.budget->kept, result.count_after);
        // Measured again from the file: the same drop (against renders of the unpruned scene).
        const eval::Quality quality = eval::measure_quality(renderer, written, targets, settings, false);
        if (std::isinf(result.budget->psnr))  // nothing that shows was dropped
            EXPECT_EQ(quality.mean_psnr, result.budget->psnr) << budget;
        else
            EXPECT_NEAR(quality.mean_psnr, result.budget->psnr, 1e-6) << budget;
        kept.push_back(result.count_after);
    }
    EXPECT_LT(kept[1], kept[0]) << "a looser budget drops more";
    EXPECT_LT(kept[1], cloud.size());
}

TEST_F(ClusterPrune, NoiseRegionMapsWarnAndStillGiveAScene) {
    Renderer renderer(context());
    const fs::path noise = dir / "noise";
    fs::create_directories(noise);
    std::mt19937 random(1);
    for (size_t v = 0; v < cameras.size(); ++v) {
        std::vector<int32_t> ids(128 * 96);
        for (auto& id : ids) id = int32_t(random() % 3000);
        char name[32];
        std::snprintf(name, sizeof(name), "view_%04zu.npy", v);
        io::write_npy(noise / name, ids.data(), {96, 128});
    }
    jobs::ClusterStageIo io{dir / "work", io::WriteMode::refuse_existing, log, {}};
    jobs::regions_stage(renderer, cloud, cameras, options, noise, io);
    jobs::project_stage(renderer, context(), cloud, cameras, options, io);
    EXPECT_NE(lines.find("warning: the view filter dropped all 8 views"), std::string::npos) << lines;
    EXPECT_NE(lines.find("regions (maximum 1000): noise rather than parts"), std::string::npos) << lines;
    jobs::build_stage(cloud, options, io);
    EXPECT_NE(lines.find("Gaussians are their own cluster"), std::string::npos) << lines;
    jobs::score_stage(cloud, cameras, options, io);
    const auto result = jobs::prune_stage(cloud, options, dir / "out.ply", io);
    EXPECT_GT(result.count_after, 0u);
}

// The contribution the projection stage measures, on splats whose answer is known: a large opaque
// splat in front, a small one right behind it (hidden), one beside the picture (off-screen) and a
// faint one in the open. The hidden and off-screen ones paint nothing, so the default selection
// drops them first, and the front one stays.
TEST_F(ClusterPrune, ContributionIsWhatEachSplatPaints) {
    GaussianCloud scene;
    scene.sh_degree = 0;
    add_splat(scene, {.position = {0, 0, 4}, .scale = {0.5, 0.5, 0.05}, .opacity = 0.99, .color = {1, 0, 0}});
    add_splat(scene, {.position = {0, 0, 5}, .scale = {0.05, 0.05, 0.05}, .opacity = 0.9, .color = {0, 1, 0}});
    add_splat(scene, {.position = {40, 0, 4}, .scale = {0.2, 0.2, 0.2}, .opacity = 0.9, .color = {0, 0, 1}});
    add_splat(scene, {.position = {1.2, 0.8, 4}, .scale = {0.1, 0.1, 0.1}, .opacity = 0.3, .color = {1, 1, 1}});
    const std::vector<Camera> views{forward_camera(96, 64, 60), forward_camera(96, 64, 60)};
    jobs::RegionView whole;
    whole.map = {96, 64, std::vector<int32_t>(96 * 64, 0)};
    Renderer renderer(context());
    const jobs::ProjectedViews projected =
        jobs::project_views(renderer, context(), scene, views, {&whole, &whole}, options);
    ASSERT_EQ(projected.contribution.size(), 4u);
    const auto& c = projected.contribution;
    // Unoccluded, a splat paints opacity * 2 pi sigma^2 pixels (sigma in pixels: scale * focal / z):
    // 0.99 * 2 pi * 7.5^2 of the 96 x 64 for the front one, 0.3 * 2 pi * 1.5^2 for the faint one
    // (coarser: it is only a few pixels wide).
    const double pixels = 96.0 * 64.0;
    EXPECT_NEAR(c[0], 0.99 * 2 * M_PI * 7.5 * 7.5 / pixels, 0.005);
    EXPECT_LT(c[1], 1e-3f * c[0]) << "hidden behind the front splat";
    EXPECT_EQ(c[2], 0.0f) << "off-screen";
    EXPECT_NEAR(c[3], 0.3 * 2 * M_PI * 1.5 * 1.5 / pixels, 0.3 * 0.3 * 2 * M_PI * 1.5 * 1.5 / pixels);

    // Each splat its own cluster: half of them go, the two that paint nothing.
    const cluster::ClusterScores scores = cluster::score_clusters(
        scene.positions, std::vector<int32_t>{0, 1, 2, 3}, projected.labels, views, options.weights, c);
    const cluster::ClusterSelection selection =
        cluster::select_clusters(scores, std::vector<int32_t>{0, 1, 2, 3}, options.selection);
    EXPECT_EQ(selection.keep, (std::vector<uint8_t>{1, 0, 0, 1}));
}

TEST_F(ClusterPrune, AViewWithoutTheSubjectIsDropped) {
    Renderer renderer(context());
    // The last camera looks away from the ball.
    cameras.push_back(Camera::look_at({0.0, 0.0, 4.0}, {0.0, 0.0, 20.0}, {0.0, 1.0, 0.0}, 128, 96, 80.0, 80.0));
    jobs::ClusterStageIo io{dir, io::WriteMode::refuse_existing, log, {}};
    options.max_views = 9;
    jobs::regions_stage(renderer, cloud, cameras, options, std::nullopt, io);
    jobs::project_stage(renderer, context(), cloud, cameras, options, io);
    EXPECT_NE(lines.find("view 8 dropped: no subject"), std::string::npos) << lines;
    const auto used = io::read_npy(dir / "projection_views.npy").values<int32_t>();
    EXPECT_EQ(std::count(used.begin(), used.end(), 8), 0);
}

}  // namespace
}  // namespace vksplat::test
