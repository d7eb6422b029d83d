// Training from photos end to end: a generated scene rendered to photos and written as a COLMAP
// folder (text model, points3D.txt near the true centres), trained for a few hundred iterations
// with densification, must reproduce the held-out views; and the loaders on the real folders.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "support/gpu_fixture.hpp"
#include "support/scenes.hpp"
#include "support/scratch_dir.hpp"
#include "support/test_data.hpp"
#include "vksplat/error.hpp"
#include "vksplat/eval/metrics.hpp"
#include "vksplat/io/image.hpp"
#include "vksplat/io/sfm_points.hpp"
#include "vksplat/jobs/train_scene.hpp"
#include "vksplat/reference/sh.hpp"
#include "vksplat/render/renderer.hpp"

namespace vksplat::test {
namespace {

namespace fs = std::filesystem;

// A ring of views at 64x48: small, since on lavapipe a training step's time goes mostly to the
// per-pixel passes, and large enough for growth to pay.
constexpr int kWidth = 64, kHeight = 48;

// The focal length is 0.6875 of the width (55 pixels at 80 wide): one field of view at any size.
std::vector<Camera> ring_of_views(int count, int width, int height) {
    const double focal = 0.6875 * width;
    std::vector<Camera> cameras;
    for (int i = 0; i < count; ++i) {
        const double angle = 2.0 * M_PI * i / count;
        Camera camera = Camera::look_at({4.0 * std::sin(angle), 0.8 * std::cos(2.0 * angle), -4.0 * std::cos(angle)},
                                        {0.0, 0.0, 0.0}, {0.0, -1.0, 0.0}, width, height, focal, focal);
        char name[32];
        std::snprintf(name, sizeof(name), "view_%02d.png", i);
        camera.name = name;
        cameras.push_back(camera);
    }
    return cameras;
}

// The scene's photos and a COLMAP text model of its cameras, with SfM points at the true centres
// moved by `noise` and coloured by each Gaussian's base colour.
void write_colmap_folder(const fs::path& dir, const GaussianCloud& truth, const std::vector<Camera>& cameras,
                         Renderer& renderer, float noise) {
    fs::create_directories(dir / "sparse" / "0");
    fs::create_directories(dir / "images");
    renderer.set_scene(truth);
    std::ofstream camera_file(dir / "sparse" / "0" / "cameras.txt"), image_file(dir / "sparse" / "0" / "images.txt");
    camera_file.precision(12);
    image_file.precision(12);
    const Camera& first = cameras.front();
    camera_file << "1 PINHOLE " << first.width << ' ' << first.height << ' ' << first.fx << ' ' << first.fy << ' '
                << first.cx << ' ' << first.cy << '\n';
    for (size_t i = 0; i < cameras.size(); ++i) {
        const RenderOutput photo = renderer.render(cameras[i]);
        io::write_png_rgb(dir / "images" / cameras[i].name, photo.width, photo.height, photo.rgb.data(), 8);
        const glm::dquat q = glm::quat_cast(cameras[i].rotation);
        const glm::dvec3 t = cameras[i].translation;
        image_file << i + 1 << ' ' << q.w << ' ' << q.x << ' ' << q.y << ' ' << q.z << ' ' << t.x << ' ' << t.y << ' '
                   << t.z << " 1 " << cameras[i].name << "\n\n";
    }
    std::ofstream points(dir / "sparse" / "0" / "points3D.txt");
    points.precision(9);
    std::mt19937 rng(1);
    std::normal_distribution<float> jitter(0.0f, noise);
    const int stride = truth.sh_coefficients() * 3;
    for (size_t i = 0; i < truth.size(); ++i) {
        points << i + 1;
        for (int k = 0; k < 3; ++k) points << ' ' << truth.positions[3 * i + k] + jitter(rng);
        for (int k = 0; k < 3; ++k) {
            const double c = 0.5 + reference::kShC0 * truth.sh[i * stride + k];
            points << ' ' << int(std::lround(std::clamp(c, 0.0, 1.0) * 255.0));
        }
        points << " 0.5\n";
    }
}

// A generated scene of 150 Gaussians (SH degree 1) photographed by a ring of 40 cameras at 64x48,
// written as a COLMAP folder; every 8th view is held out.
class TrainScene : public GpuTest {
protected:
    void make_data(const std::string& name) {
        dir = fresh_test_dir(name);
        truth = random_scene(3, 150, 1, 4.0f, 6.0f, 0.05f, 0.2f, 1.5f);
        for (size_t i = 0; i < truth.size(); ++i) {
            truth.positions[3 * i + 2] -= 5.0f;
            truth.opacity_logits[i] = std::clamp(truth.opacity_logits[i], 0.0f, 3.0f);
        }
        cameras = ring_of_views(40, kWidth, kHeight);
        renderer = std::make_unique<Renderer>(context());
        write_colmap_folder(dir / "data", truth, cameras, *renderer, 0.05f);
    }
    // The reference recipe shrunk to `iterations` steps at this size: SH degree 1 from step 200,
    // densification every 100 steps from 100 until `densify_until` (0: never), no opacity reset
    // (recovering from one takes thousands of steps).
    static jobs::TrainRecipe recipe(uint64_t iterations, uint64_t densify_until) {
        jobs::TrainRecipe r;
        r.iterations = iterations;
        r.sh_degree = 1;
        r.sh_degree_interval = 200;
        r.densify_from = 100;
        r.strategy = jobs::DensifyStrategy::reference;
        r.densify_until = r.budget.densify_until = r.lean.densify_until = densify_until;
        r.densify_interval = 100;
        r.opacity_reset_interval = 100000;
        return r;
    }
    jobs::TrainResult train(const jobs::TrainingData& data, const jobs::TrainRecipe& r, const std::string& out) {
        jobs::TrainOptions options;
        options.recipe = r;
        options.out_dir = dir / out;
        // Fixed-point sums: each run's result is the same every time, so that a comparison of two
        // recipes does not change with the order of float additions (it did, by up to 0.4 dB).
        options.deterministic = true;
        const jobs::TrainResult result =
            jobs::train_scene(context(), data, jobs::photos_in_folder(data.images_dir, {0, 0, 0}), options, measure());
        std::printf("  %zu -> %zu Gaussians, held-out PSNR %.2f dB, %.1f s\n", data.initial.size(), result.gaussians,
                    result.test.mean_psnr, result.seconds);
        return result;
    }
    jobs::TestMeasure measure() {
        return [this](const GaussianCloud& scene, const eval::TestViews& views) {
            return eval::measure_quality(*renderer, scene, views, RenderSettings{}, false);
        };
    }
    fs::path dir;
    GaussianCloud truth;
    std::vector<Camera> cameras;
    std::unique_ptr<Renderer> renderer;
};

TEST_F(TrainScene, AColmapFolderTrainsToItsHeldOutViews) {
    make_data("train_scene_colmap");
    const jobs::TrainRecipe r = recipe(300, 0);
    jobs::TrainingData data = jobs::load_training_data(dir / "data", r, 1.0, 0);
    EXPECT_EQ(data.format, "colmap");
    EXPECT_EQ(data.test_views.size(), 5u);
    EXPECT_EQ(data.train_views.size(), 35u);
    EXPECT_EQ(data.initial.size(), truth.size());
    for (size_t i = 0; i < cameras.size(); ++i) {
        for (int row = 0; row < 3; ++row)
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(data.cameras[i].rotation[c][row], cameras[i].rotation[c][row], 1e-6) << i;
        ASSERT_NEAR(glm::length(data.cameras[i].centre() - cameras[i].centre()), 0.0, 1e-4) << i;
    }

    // From the true Gaussians, perturbed, a few hundred steps of the loop (view order, SH schedule,
    // position decay) must recover views they were not fitted to. Densification is off here: it
    // splits what is already right, which costs ~9 dB that 400 steps do not win back (measured);
    // the next test shows it where it belongs.
    data.initial = truth;
    std::mt19937 rng(7);
    std::normal_distribution<float> noise(0.0f, 1.0f);
    for (auto& v : data.initial.positions) v += 0.03f * noise(rng);
    for (auto& v : data.initial.log_scales) v += 0.2f * noise(rng);
    for (auto& v : data.initial.opacity_logits) v += 0.5f * noise(rng);
    for (auto& v : data.initial.sh) v += 0.1f * noise(rng);
    const jobs::TrainResult result = train(data, r, "out");
    EXPECT_GE(result.test.mean_psnr, 30.0);
    EXPECT_EQ(result.iterations, 300u);
    EXPECT_EQ(result.skipped, 0u);
    for (const auto& file : {result.ply, result.cameras_json, result.metrics_json}) EXPECT_TRUE(fs::exists(file)) << file;
    // A second run into the same folder is refused before any work.
    jobs::TrainOptions again;
    again.recipe = r;
    again.out_dir = dir / "out";
    EXPECT_THROW(jobs::train_scene(context(), data, jobs::photos_in_folder(data.images_dir, {0, 0, 0}), again, measure()),
                 InputError);
}

// From the SfM points (the true centres moved by 0.05, isotropic kNN scales, point colours), the
// reference recipe with the reference threshold of 0.0002: growth must pay on the held-out views
// within 800 steps (measured: 23.1 dB without, 25.2 dB with, 150 -> ~1,500 Gaussians). The lean
// recipe (what `train` runs without a budget: the same growth until 600, then settled in three
// rounds to the Gaussians that carry 99% of the blend weight) must keep fewer Gaussians than the
// reference at nearly its quality (measured: ~860 at 26.4 dB). One test, so that lavapipe trains
// the reference run once for both comparisons.
TEST_F(TrainScene, GrowthBeatsNoneAndTheLeanRecipeKeepsWhatCarriesThePicture) {
    make_data("train_scene_sfm");
    const jobs::TrainingData data = jobs::load_training_data(dir / "data", recipe(800, 0), 1.0, 0);
    const jobs::TrainResult fixed = train(data, recipe(800, 0), "fixed");
    const jobs::TrainResult reference = train(data, recipe(800, 600), "reference");
    EXPECT_EQ(fixed.gaussians, truth.size());
    EXPECT_GT(reference.gaussians, 3 * truth.size());
    EXPECT_GT(reference.test.mean_psnr, fixed.test.mean_psnr + 1.5);

    jobs::TrainRecipe r = recipe(800, 600);
    r.strategy = jobs::DensifyStrategy::automatic;
    const jobs::TrainResult lean = train(data, r, "lean");
    EXPECT_EQ(lean.strategy, "lean");
    EXPECT_EQ(lean.importance_prunes.prune_events, 3u);
    EXPECT_LT(lean.gaussians, reference.gaussians);
    EXPECT_GT(lean.test.mean_psnr, reference.test.mean_psnr - 0.5);
}

TEST_F(TrainScene, TheLeanRecipesShareMustBeAShare) {
    make_data("train_scene_lean_share");
    jobs::TrainRecipe r = recipe(800, 600);
    r.strategy = jobs::DensifyStrategy::automatic;
    const jobs::TrainingData data = jobs::load_training_data(dir / "data", r, 1.0, 0);
    for (const double share : {0.0, -0.5, 1.5, std::nan("")}) {
        r.lean.keep_share = share;
        EXPECT_THROW(train(data, r, "lean_none"), InputError) << share;
        EXPECT_FALSE(fs::exists(dir / "lean_none")) << "refused before any output";
    }
}

// A budget of about half the Gaussians the reference recipe grows here (~1,500, the test above):
// the budget recipe (scheduled growth past the budget, settled to it by blend weight after
// densification) loses less on the held-out views than the reference recipe capped there, whose
// growth stops once the first candidates fill the cap (measured: 26.4 against 24.3 dB).
TEST_F(TrainScene, ABudgetLosesLessThanTheCapAtHalfTheCount) {
    make_data("train_scene_budget");
    jobs::TrainRecipe half = recipe(800, 600);
    half.densify.max_gaussians = 720;
    const jobs::TrainingData data = jobs::load_training_data(dir / "data", half, 1.0, 0);
    half.strategy = jobs::DensifyStrategy::reference;
    const jobs::TrainResult capped = train(data, half, "capped");
    half.strategy = jobs::DensifyStrategy::automatic;
    const jobs::TrainResult budget = train(data, half, "budget");
    EXPECT_EQ(budget.strategy, "budget");
    EXPECT_LE(budget.gaussians, half.densify.max_gaussians);
    EXPECT_LE(capped.gaussians, half.densify.max_gaussians);
    // The cap binds: the reference recipe would grow past it.
    EXPECT_GT(capped.gaussians, half.densify.max_gaussians * 9 / 10);
    EXPECT_GT(budget.test.mean_psnr, capped.test.mean_psnr + 0.3);
    // metrics.json has the count over the run, report.html its chart.
    EXPECT_TRUE(fs::exists(dir / "budget" / "report.html"));
    EXPECT_TRUE(fs::exists(dir / "budget" / "training_gaussians.svg"));
    ASSERT_FALSE(budget.history.empty());
    EXPECT_EQ(budget.history.back().iteration, 800u);
    EXPECT_EQ(budget.history.back().gaussians, budget.gaussians);
}

// 3DGS-MCMC through the job, its refinements as often as a short run allows: from a random half of
// the budget it grows by copies and fills the budget exactly. (Its quality is not asserted: on
// bonsai and lego it trails the budget recipe; benchmarks/RESULTS.md.)
TEST_F(TrainScene, McmcGrowsToItsBudgetExactly) {
    make_data("train_scene_mcmc");
    jobs::TrainRecipe r = recipe(300, 0);
    r.strategy = jobs::DensifyStrategy::mcmc;
    r.densify.max_gaussians = 120;
    r.mcmc.refine_from = 50;
    r.mcmc.refine_until = 300;
    r.mcmc.refine_every = 50;
    r.mcmc.growth = 1.3;
    const jobs::TrainingData data = jobs::load_training_data(dir / "data", r, 1.0, 0);
    const jobs::TrainResult mcmc = train(data, r, "mcmc");
    EXPECT_EQ(mcmc.strategy, "mcmc");
    EXPECT_EQ(mcmc.gaussians, 120u);
    EXPECT_GT(mcmc.mcmc_events.added, 0u);
}

TEST_F(TrainScene, TheMemoryBudgetCapsGrowthAndRefusesAStartThatCannotFit) {
    make_data("train_scene_budget");
    const jobs::TrainRecipe r = recipe(300, 250);
    const jobs::TrainingData data = jobs::load_training_data(dir / "data", r, 1.0, 0);
    // The smallest budget (in steps of 16 KB) that holds 300 Gaussians at 64x48.
    uint64_t budget = 1 << 20;
    while (jobs::gaussians_within(budget, 1, kWidth * kHeight) < 300) budget += 1 << 14;
    const size_t room = jobs::gaussians_within(budget, 1, kWidth * kHeight);
    jobs::TrainOptions options;
    options.recipe = r;
    options.memory_budget = budget;
    options.out_dir = dir / "capped";
    const jobs::TrainResult capped =
        jobs::train_scene(context(), data, jobs::photos_in_folder(data.images_dir, {0, 0, 0}), options, measure());
    EXPECT_GT(capped.gaussians, truth.size());  // it grew (to ~1,500 without the budget) ...
    EXPECT_LE(capped.gaussians, room);          // ... as far as the budget holds
    EXPECT_LE(capped.peak_device_bytes, budget);  // transients included
    options.memory_budget = budget / 4;
    options.out_dir = dir / "too_small";
    try {
        jobs::train_scene(context(), data, jobs::photos_in_folder(data.images_dir, {0, 0, 0}), options, measure());
        FAIL() << "a start beyond the memory budget was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("--memory-budget"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(dir / "too_small" / "point_cloud.ply"));
}

TEST_F(TrainScene, WithNoHeldOutViewsNoTestQualityIsWritten) {
    // --test-every 0 holds no view out: metrics.json must say there is no test PSNR, not 0 dB.
    make_data("train_scene_no_test_views");
    jobs::TrainRecipe r = recipe(10, 0);
    r.test_every = 0;
    const jobs::TrainingData data = jobs::load_training_data(dir / "data", r, 1.0, 0);
    EXPECT_TRUE(data.test_views.empty());
    const jobs::TrainResult result = train(data, r, "out");
    EXPECT_TRUE(result.test.psnr.empty());
    std::ifstream in(result.metrics_json);
    const nlohmann::json metrics = nlohmann::json::parse(in);
    EXPECT_EQ(metrics["test_views"], 0);
    EXPECT_TRUE(metrics["test_psnr"].is_null()) << metrics["test_psnr"];
    EXPECT_TRUE(metrics["test_ssim"].is_null()) << metrics["test_ssim"];
}

TEST_F(TrainScene, UndistortsLensesItCanAndRefusesOtherModelsAndMissingData) {
    const fs::path dir = fresh_test_dir("train_scene_refusals");
    EXPECT_THROW(jobs::load_training_data(dir, {}, 1.0, 0), InputError);
    fs::create_directories(dir / "sparse" / "0");
    std::ofstream(dir / "sparse" / "0" / "cameras.txt") << "1 OPENCV_FISHEYE 64 48 50 50 32 24 0.1 0.01 0 0\n";
    std::ofstream(dir / "sparse" / "0" / "images.txt") << "1 1 0 0 0 0 0 4 1 a.png\n\n";
    std::ofstream(dir / "sparse" / "0" / "points3D.txt") << "1 0 0 0 255 0 0 0.5\n";
    jobs::TrainRecipe all_train;
    all_train.test_every = 0;
    try {
        jobs::load_training_data(dir, all_train, 1.0, 0);
        FAIL() << "a fisheye camera model was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("model OPENCV_FISHEYE is not supported"), std::string::npos) << e.what();
    }

    // OPENCV is undistorted (io/undistort_test.cpp checks how well): a pinhole camera, and its
    // photo remapped when photos_in_folder reads it with the data's undistortion.
    std::ofstream(dir / "sparse" / "0" / "cameras.txt") << "1 OPENCV 64 48 50 50 32 24 0.1 0.01 0 0\n";
    fs::create_directories(dir / "images");
    std::vector<float> ramp(64 * 48 * 3);
    for (size_t i = 0; i < ramp.size(); ++i) ramp[i] = float(i % 192) / 191;
    io::write_png_rgb(dir / "images" / "a.png", 64, 48, ramp.data(), 16);
    const jobs::TrainingData data = jobs::load_training_data(dir, all_train, 1.0, 0);
    ASSERT_EQ(data.notices.size(), 1u);
    EXPECT_NE(data.notices[0].find("photos undistorted to PINHOLE"), std::string::npos) << data.notices[0];
    EXPECT_NE(data.cameras[0].fx, 50.0);
    const io::ImageRGB photo = io::read_image_rgb(dir / "images" / "a.png", {0, 0, 0});
    const io::ImageRGB read = jobs::photos_in_folder(data.images_dir, {0, 0, 0}, 1.0, data.undistortion)(data.cameras[0]);
    EXPECT_EQ(read.width, 64);
    EXPECT_NE(read.rgb, photo.rgb);
}

TEST(TrainingData, AnInriaFolderIsSplitByItsSplitFields) {
    const fs::path dir = fresh_test_dir("train_scene_inria_split");
    fs::create_directories(dir / "images");
    const auto write = [&](bool with_split, bool first_only = false) {
        std::ofstream out(dir / "cameras.json");
        out << "[";
        for (int i = 0; i < 4; ++i) {
            const double angle = 2.0 * M_PI * i / 4;
            out << (i ? "," : "") << "{\"id\": " << i << ", \"img_name\": \"v" << i << "\", \"width\": 32, \"height\": 24, "
                << "\"position\": [" << 4 * std::sin(angle) << ", 0, " << -4 * std::cos(angle) << "], "
                << "\"rotation\": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], \"fx\": 30, \"fy\": 30";
            if (with_split && (!first_only || i == 0))
                out << ", \"split\": \"" << (i % 2 ? "test" : "train") << "\"";
            out << "}";
        }
        out << "]";
    };
    jobs::TrainRecipe recipe;
    recipe.random_points = 100;
    write(true);
    jobs::TrainingData data = jobs::load_training_data(dir, recipe, 1.0, 0);
    EXPECT_EQ(data.format, "inria");
    EXPECT_EQ(data.test_views, (std::vector<size_t>{1, 3}));
    EXPECT_EQ(data.train_views, (std::vector<size_t>{0, 2}));
    EXPECT_EQ(data.initial.size(), 100u);
    // Without split fields, fewer than 13 cameras are all test and all training views.
    write(false);
    data = jobs::load_training_data(dir, recipe, 1.0, 0);
    EXPECT_EQ(data.test_views.size(), 4u);
    EXPECT_EQ(data.train_views.size(), 4u);
    // A split on some cameras only is no split: the same convention, not a refusal.
    write(true, true);
    data = jobs::load_training_data(dir, recipe, 1.0, 0);
    EXPECT_EQ(data.test_views.size(), 4u);
    EXPECT_EQ(data.train_views.size(), 4u);
}

TEST(SfmPoints, ReadTheRealFolders) {
    VKSPLAT_REQUIRE_SHARED_DATA();
    const auto bonsai = io::read_sfm_points(shared_data_dir() / "bonsai" / "sparse" / "0");
    EXPECT_EQ(bonsai.size(), 73404u);
    const auto snowmiku = io::read_sfm_points(shared_data_dir() / "snowmiku" / "sparse" / "0");
    EXPECT_GT(snowmiku.size(), 1000u);
    for (float c : snowmiku.colors) ASSERT_TRUE(c >= 0.0f && c <= 1.0f);
    const jobs::TrainingData data = jobs::load_training_data(shared_data_dir() / "bonsai", {}, 1.0, 0);
    EXPECT_EQ(data.format, "colmap");
    EXPECT_EQ(data.cameras.size(), 291u);
    EXPECT_EQ(data.test_views.size(), 37u);  // every 8th of 291 by name, as the reference splits it
    EXPECT_EQ(data.initial.size(), 73404u);
}

}  // namespace
}  // namespace vksplat::test
