// render_views: the files it writes, metrics against photos, and its refusals.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "support/gpu_fixture.hpp"
#include "support/scenes.hpp"
#include "vksplat/demo_scene.hpp"
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

}  // namespace
}  // namespace vksplat::test
