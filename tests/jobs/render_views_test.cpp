// render_views: the files it writes, metrics against photos, and its refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "support/gpu_fixture.hpp"
#include "support/scenes.hpp"
#include "vksplat/scene/demo_scene.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/image.hpp"
#include "vksplat/io/npy.hpp"
#include "vksplat/jobs/render_views.hpp"

namespace vksplat::test {
namespace {

namespace fs = std::filesystem;

class RenderViews : public GpuTest {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("vksplat_render_views_" + std::to_string(::getpid()) + "_" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir);
        renderer = std::make_unique<Renderer>(context());
        renderer->set_scene(make_demo_scene());
        cameras = make_orbit_cameras(3, 64, 48, 4.0, 25.0);
    }
    void TearDown() override {
        fs::remove_all(dir);
        GpuTest::TearDown();
    }
    fs::path dir;
    std::unique_ptr<Renderer> renderer;
    std::vector<Camera> cameras;
};

TEST_F(RenderViews, WritesImagesAlphaAndDepth) {
    jobs::RenderViewsOptions options;
    options.out_dir = dir / "out";
    options.views = {0, 2};
    options.write_alpha = true;
    options.write_depth = true;
    options.bit_depth = 16;
    const auto result = jobs::render_views(*renderer, cameras, options);
    ASSERT_EQ(result.views.size(), 2u);
    EXPECT_FALSE(result.has_metrics);
    for (const char* name : {"orbit_000", "orbit_002"}) {
        EXPECT_TRUE(fs::exists(options.out_dir / (std::string(name) + ".png"))) << name;
        EXPECT_TRUE(fs::exists(options.out_dir / (std::string(name) + ".alpha.png"))) << name;
        const io::NpyArray depth = io::read_npy(options.out_dir / (std::string(name) + ".depth.npy"));
        EXPECT_EQ(depth.shape, (std::vector<size_t>{48, 64}));
        EXPECT_EQ(depth.dtype, io::NpyDtype::float32);
    }
    EXPECT_FALSE(fs::exists(options.out_dir / "orbit_001.png"));
    const io::ImageRGB image = io::read_image_rgb(options.out_dir / "orbit_000.png", {0, 0, 0});
    EXPECT_EQ(image.width, 64);
    EXPECT_EQ(image.height, 48);
}

TEST_F(RenderViews, RefusesToOverwriteWithoutBeingAsked) {
    jobs::RenderViewsOptions options;
    options.out_dir = dir;
    options.views = {1};
    jobs::render_views(*renderer, cameras, options);
    EXPECT_THROW(jobs::render_views(*renderer, cameras, options), std::exception);
    options.mode = io::WriteMode::overwrite;
    EXPECT_NO_THROW(jobs::render_views(*renderer, cameras, options));
}

TEST_F(RenderViews, ScoresAgainstPhotosAndWritesMetrics) {
    // "Photos" = the renders themselves, saved as 16-bit PNG: PSNR must be very high.
    jobs::RenderViewsOptions photos;
    photos.out_dir = dir / "photos";
    photos.bit_depth = 16;
    jobs::render_views(*renderer, cameras, photos);

    jobs::RenderViewsOptions options;
    options.out_dir = dir / "out";
    options.images_dir = photos.out_dir;
    const auto result = jobs::render_views(*renderer, cameras, options);
    ASSERT_TRUE(result.has_metrics);
    EXPECT_GT(result.mean_psnr, 80.0);
    EXPECT_GT(result.mean_ssim, 0.999);
    std::ifstream csv(result.metrics_csv);
    std::string header, line;
    std::getline(csv, header);
    EXPECT_EQ(header, "view,name,psnr,ssim");
    int rows = 0;
    while (std::getline(csv, line)) ++rows;
    EXPECT_EQ(rows, 4);  // three views and the mean
}

TEST_F(RenderViews, PhotoOfTheWrongSizeIsNamed) {
    jobs::RenderViewsOptions photos;
    photos.out_dir = dir / "photos";
    jobs::render_views(*renderer, make_orbit_cameras(3, 32, 32, 4.0, 25.0), photos);
    jobs::RenderViewsOptions options;
    options.out_dir = dir / "out";
    options.images_dir = photos.out_dir;
    try {
        jobs::render_views(*renderer, cameras, options);
        FAIL() << "a photo of the wrong size was accepted";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("orbit_000.png"), std::string::npos) << message;
        EXPECT_NE(message.find("photo is 32x32 but camera 'orbit_000' renders 64x48"), std::string::npos) << message;
    }
}

// The last view's photo is of the wrong size: refused before the first view is written.
TEST_F(RenderViews, APhotoOfTheWrongSizeIsRefusedBeforeAnyViewIsWritten) {
    jobs::RenderViewsOptions photos;
    photos.out_dir = dir / "photos";
    jobs::render_views(*renderer, cameras, photos);
    jobs::RenderViewsOptions small = photos;
    small.out_dir = dir / "small";
    jobs::render_views(*renderer, make_orbit_cameras(3, 32, 32, 4.0, 25.0), small);
    fs::copy_file(small.out_dir / "orbit_002.png", photos.out_dir / "orbit_002.png", fs::copy_options::overwrite_existing);
    jobs::RenderViewsOptions options;
    options.out_dir = dir / "out";
    options.images_dir = photos.out_dir;
    EXPECT_THROW(jobs::render_views(*renderer, cameras, options), InputError);
    EXPECT_FALSE(fs::exists(options.out_dir / "orbit_000.png"));
}

TEST_F(RenderViews, MissingPhotoIsNamed) {
    jobs::RenderViewsOptions options;
    options.out_dir = dir / "out";
    options.images_dir = dir;  // exists, holds no photos
    fs::create_directories(dir);
    try {
        jobs::render_views(*renderer, cameras, options);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("orbit_000"), std::string::npos) << e.what();
    }
}

// Every output is checked before the first is written: a run refused halfway would leave some
// views written and others not.
void expect_refusal_naming(const std::function<void()>& run, const std::vector<std::string>& words) {
    try {
        run();
        ADD_FAILURE() << "not refused";
    } catch (const InputError& e) {
        for (const auto& word : words) EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
    }
}

TEST_F(RenderViews, RefusesAViewNamedTwice) {
    jobs::RenderViewsOptions options;
    options.out_dir = dir / "out";
    options.views = {0, 2, 0};
    expect_refusal_naming([&] { jobs::render_views(*renderer, cameras, options); }, {"view 0", "twice"});
    EXPECT_FALSE(fs::exists(options.out_dir / "orbit_000.png"));
    EXPECT_FALSE(fs::exists(options.out_dir)) << "a refused run leaves no empty folder";
}

TEST_F(RenderViews, CamerasWhoseNamesCollideGetDistinctFiles) {
    // One name twice, and the same file name in two folders: the first in the camera file's order
    // keeps the plain name, the next ones get -2, -3, ...
    cameras[0].name = "a/x.jpg";
    cameras[1].name = "b/x.jpg";
    cameras[2].name = "a/x.jpg";
    jobs::RenderViewsOptions photos;
    photos.out_dir = dir / "photos";
    jobs::render_views(*renderer, cameras, photos);
    for (const char* name : {"x.png", "x-2.png", "x-3.png"}) EXPECT_TRUE(fs::exists(photos.out_dir / name)) << name;

    // The names do not depend on which views are rendered: view 2 alone is still x-3.
    jobs::RenderViewsOptions one;
    one.out_dir = dir / "one";
    one.views = {2};
    const auto result = jobs::render_views(*renderer, cameras, one);
    ASSERT_EQ(result.views.size(), 1u);
    EXPECT_EQ(result.views[0].name, "x-3");
    EXPECT_EQ(result.views[0].image, one.out_dir / "x-3.png");
    EXPECT_FALSE(fs::exists(one.out_dir / "x.png"));
}

TEST_F(RenderViews, ChecksEveryOutputBeforeTheFirstWrite) {
    jobs::RenderViewsOptions options;
    options.out_dir = dir / "out";
    options.write_alpha = true;
    fs::create_directories(options.out_dir);
    std::ofstream(options.out_dir / "orbit_002.alpha.png") << "mine";
    expect_refusal_naming([&] { jobs::render_views(*renderer, cameras, options); }, {"orbit_002.alpha.png", "--force"});
    EXPECT_FALSE(fs::exists(options.out_dir / "orbit_000.png")) << "nothing is written before every output is checked";

    // metrics.csv, written last, is checked first too.
    fs::remove(options.out_dir / "orbit_002.alpha.png");
    jobs::RenderViewsOptions photos;
    photos.out_dir = dir / "photos";
    jobs::render_views(*renderer, cameras, photos);
    options.images_dir = photos.out_dir;
    std::ofstream(options.out_dir / "metrics.csv") << "mine";
    expect_refusal_naming([&] { jobs::render_views(*renderer, cameras, options); }, {"metrics.csv", "--force"});
    EXPECT_FALSE(fs::exists(options.out_dir / "orbit_000.png"));
}

TEST_F(RenderViews, NeverWritesOverItsPhotos) {
    jobs::RenderViewsOptions photos;
    photos.out_dir = dir / "photos";
    photos.bit_depth = 16;
    jobs::render_views(*renderer, cameras, photos);
    const auto size = fs::file_size(photos.out_dir / "orbit_000.png");

    jobs::RenderViewsOptions options;
    options.out_dir = photos.out_dir;
    options.images_dir = photos.out_dir;
    options.mode = io::WriteMode::overwrite;  // --force or not
    expect_refusal_naming([&] { jobs::render_views(*renderer, cameras, options); }, {"orbit_000.png", "input"});
    EXPECT_EQ(fs::file_size(photos.out_dir / "orbit_000.png"), size) << "the 16-bit photo is still there";
}

TEST(OutputStems, DistinctAndIndependentOfTheViewsRendered) {
    std::vector<Camera> cameras(7);
    const char* names[] = {"images/r_0.png", "a/x.jpg", "b/x.jpg", "x-2", "", "x.png", "a/x.jpg"};
    for (size_t i = 0; i < cameras.size(); ++i) cameras[i].name = names[i];
    // "x-2" is a camera's own name, so the copies of x skip it.
    EXPECT_EQ(jobs::output_stems(cameras),
              (std::vector<std::string>{"r_0", "x", "x-3", "x-2", "view_0004", "x-4", "x-5"}));
}

TEST_F(RenderViews, NeverWritesOverItsSceneOrCameras) {
    fs::create_directories(dir);
    std::ofstream(dir / "orbit_001.png") << "a scene file by an unlucky name";
    jobs::RenderViewsOptions options;
    options.out_dir = dir;
    options.mode = io::WriteMode::overwrite;
    options.inputs = {dir / "orbit_001.png"};
    expect_refusal_naming([&] { jobs::render_views(*renderer, cameras, options); }, {"orbit_001.png", "input"});
    EXPECT_FALSE(fs::exists(dir / "orbit_000.png"));
}

TEST_F(RenderViews, ListsEveryFileItWrote) {
    jobs::RenderViewsOptions photos;
    photos.out_dir = dir / "photos";
    const auto rendered = jobs::render_views(*renderer, cameras, photos);
    EXPECT_EQ(rendered.files.size(), 3u);

    jobs::RenderViewsOptions options;
    options.out_dir = dir / "out";
    options.views = {2, 0};
    options.write_alpha = true;
    options.write_depth = true;
    options.images_dir = photos.out_dir;
    const auto result = jobs::render_views(*renderer, cameras, options);
    const fs::path& out = options.out_dir;
    EXPECT_EQ(result.files, (std::vector<fs::path>{out / "orbit_002.png", out / "orbit_002.alpha.png",
                                                   out / "orbit_002.depth.npy", out / "orbit_000.png",
                                                   out / "orbit_000.alpha.png", out / "orbit_000.depth.npy",
                                                   out / "metrics.csv"}));
    size_t on_disk = 0;
    for (const auto& entry : fs::directory_iterator(out)) on_disk += entry.is_regular_file();
    EXPECT_EQ(on_disk, result.files.size());
}

// A frame whose per-pixel buffers alone exceed the memory: chunks split the Gaussians, never the
// pixels, so the message says what the frame needs and what there is, and advises a larger budget
// only where the device holds one.
std::string frame_refusal(Renderer& renderer, int side) {
    std::vector<Camera> big = make_orbit_cameras(1, side, side, 4.0, 25.0);
    jobs::RenderViewsOptions options;
    options.out_dir = fs::temp_directory_path() / ("vksplat_render_views_" + std::to_string(::getpid()) + "_big");
    try {
        jobs::render_views(renderer, big, options);
    } catch (const GpuError& e) {
        fs::remove_all(options.out_dir);
        return e.what();
    }
    fs::remove_all(options.out_dir);
    ADD_FAILURE() << "a " << side << "x" << side << " frame rendered";
    return {};
}

TEST_F(RenderViews, AFrameBeyondTheBudgetSaysWhatItNeeds) {
    const uint64_t device = context().info().device_local_budget;
    SceneStorage storage;
    storage.memory_budget = uint64_t(64) << 20;
    renderer->set_scene(make_demo_scene(), storage);
    const std::string message = frame_refusal(*renderer, 8192);  // 64 Mi pixels: gigabytes
    EXPECT_NE(message.find("8192x8192 frame"), std::string::npos) << message;
    EXPECT_NE(message.find("per-pixel buffers"), std::string::npos) << message;
    EXPECT_NE(message.find("bytes a pixel"), std::string::npos) << message;
    // 8192 x 8192 x (24 bytes of image + the chunks' carried state) is more than 3 GiB.
    if (device < (uint64_t(3) << 30)) {
        EXPECT_EQ(message.find("raise --memory-budget"), std::string::npos) << message;
        EXPECT_NE(message.find("smaller resolution"), std::string::npos) << message;
    } else {
        EXPECT_NE(message.find("raise --memory-budget to at least"), std::string::npos) << message;
    }
}

TEST_F(RenderViews, AFrameBeyondTheDeviceSaysWhatItNeeds) {
    // The default budget (the device's own): a frame whose image buffers (24 bytes a pixel) alone
    // are half as large again as the device.
    const uint64_t device = context().info().device_local_budget;
    const int side = int(std::ceil(std::sqrt(double(device) / 24.0 * 1.5)));
    if (side > 65535) GTEST_SKIP() << "no frame of fewer than 2^32 pixels is too large for this device";
    const std::string message = frame_refusal(*renderer, side);
    const std::string size = std::to_string(side) + "x" + std::to_string(side) + " frame";
    EXPECT_NE(message.find(size), std::string::npos) << message;
    EXPECT_NE(message.find("per-pixel buffers"), std::string::npos) << message;
    EXPECT_NE(message.find("smaller resolution"), std::string::npos) << message;
    EXPECT_EQ(message.find("memory budget"), std::string::npos) << "no budget helps: " << message;
}

}  // namespace
}  // namespace vksplat::test
