// Renderer behaviour beyond the picture: determinism, growth of the tile-entry buffers, bad
// cameras, statistics.
#include <gtest/gtest.h>

#include <array>
#include <limits>
#include <string>

#include "io/io_test_helpers.hpp"
#include "support/gpu_fixture.hpp"
#include "support/scenes.hpp"
#include "vksplat/error.hpp"
#include "vksplat/render/renderer.hpp"

namespace vksplat::test {
namespace {

class RendererTest : public GpuTest {};

TEST_F(RendererTest, SameFrameTwiceIsBitIdentical) {
    Renderer renderer(context());
    renderer.set_scene(random_scene(21, 2000, 3));
    const Camera camera = forward_camera(200, 150, 150.0);
    const RenderOutput a = renderer.render(camera);
    const RenderOutput b = renderer.render(camera);
    EXPECT_EQ(a.rgb, b.rgb);
    EXPECT_EQ(a.alpha, b.alpha);
    EXPECT_EQ(a.depth, b.depth);
    EXPECT_EQ(a.contributors, b.contributors);
}

TEST_F(RendererTest, GrowsTileEntriesWhenAViewNeedsMore) {
    // Large splats touch many tiles each: far more than the initial entries-per-Gaussian guess.
    Renderer renderer(context());
    renderer.set_scene(random_scene(22, 50, 0, 2.0f, 3.0f, 0.5f, 1.0f));
    const Camera camera = forward_camera(512, 512, 400.0);
    const RenderOutput grown = renderer.render(camera);
    EXPECT_GT(renderer.last_frame().attempts, 1u);
    EXPECT_GT(renderer.last_frame().tile_entries, 50u * 4u);
    const RenderOutput again = renderer.render(camera);
    EXPECT_EQ(renderer.last_frame().attempts, 1u) << "capacity should persist between frames";
    EXPECT_EQ(grown.rgb, again.rgb);
}

TEST_F(RendererTest, MoreTileEntriesThanAFrameCanSortIsAClearError) {
    // 36,000 splats wider than a 4K view, each in all of its 32,400 tiles: 1.17e9 entries, past the
    // 2^30 at which the count saturates. A frame sized by the saturated count would drop entries
    // unseen; the renderer must say so instead.
    Renderer renderer(context());
    renderer.set_scene(random_scene(25, 36000, 0, 4.0f, 6.0f, 8.0f, 12.0f, 0.5f));
    try {
        renderer.render(forward_camera(3840, 2160, 2000.0));
        FAIL() << "rendered a view that needs more tile entries than a frame can sort";
    } catch (const GpuError& e) {
        EXPECT_NE(std::string(e.what()).find("more than one frame can sort"), std::string::npos) << e.what();
    }
}

TEST_F(RendererTest, ReportsStagesAndCounts) {
    Renderer renderer(context());
    renderer.set_scene(random_scene(23, 1000, 1));
    renderer.render(forward_camera(128, 128, 100.0));
    const FrameStats& stats = renderer.last_frame();
    EXPECT_EQ(stats.gaussians, 1000u);
    EXPECT_GT(stats.visible, 0u);
    EXPECT_LE(stats.visible, 1000u);
    EXPECT_GE(stats.tile_entries, stats.visible);
    EXPECT_GT(stats.device_bytes, 0u);
    if (context().info().timestamp_period_ns > 0) {
        ASSERT_FALSE(stats.stages.empty());
        EXPECT_EQ(stats.stages.back().stage, "blend");
        EXPECT_GT(stats.gpu_milliseconds, 0.0);
    }
}

TEST_F(RendererTest, RejectsInvalidCameras) {
    Renderer renderer(context());
    renderer.set_scene(random_scene(24, 10, 0));
    Camera camera = forward_camera(64, 64, 0.0);
    camera.name = "zero focal";
    try {
        renderer.render(camera);
        FAIL() << "a camera with zero focal length rendered";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("zero focal"), std::string::npos) << e.what();
    }
}

// 65536 x 65536 pixels counted in 32 bits is 0: refused by name before anything is sized by it.
TEST_F(RendererTest, RefusesAnImageWhosePixelsAFrameCannotIndex) {
    Renderer renderer(context());
    renderer.set_scene(random_scene(24, 10, 0));
    Camera camera = forward_camera(65536, 65536, 40000.0);
    camera.name = "huge";
    io::test::expect_input_error([&] { renderer.render(camera); },
                                 {"camera 'huge': its 65536x65536 image has more pixels"});
}

// The background shows wherever light gets through: NaN would spread into every such pixel and
// a value outside [0, 1] would be clamped away unseen when written, so neither renders.
TEST_F(RendererTest, RejectsABackgroundThatIsNotAColour) {
    Renderer renderer(context());
    renderer.set_scene(random_scene(24, 10, 0));
    const Camera camera = forward_camera(64, 64, 60.0);
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    for (const auto& background : {std::array<float, 3>{nan, 0, 0}, std::array<float, 3>{0, inf, 0},
                                   std::array<float, 3>{2, 0, 0}, std::array<float, 3>{0, 0, -0.5f}}) {
        RenderSettings settings;
        settings.background = background;
        try {
            renderer.render(camera, settings);
            ADD_FAILURE() << "rendered on background " << background[0] << ", " << background[1] << ", " << background[2];
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("background ("), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("each channel must be a finite number in [0, 1]"), std::string::npos)
                << e.what();
        }
    }
    RenderSettings white;
    white.background = {1, 1, 1};
    EXPECT_NO_THROW(renderer.render(camera, white));
}

TEST_F(RendererTest, NonFiniteInputNeverGivesANanPixel) {
    GaussianCloud cloud = random_scene(25, 200, 2);
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    cloud.positions[0] = nan;
    cloud.rotations[4 * 1 + 0] = cloud.rotations[4 * 1 + 1] = cloud.rotations[4 * 1 + 2] = cloud.rotations[4 * 1 + 3] = 0;
    cloud.log_scales[3 * 2] = inf;
    cloud.opacity_logits[3] = nan;
    cloud.sh[4 * 48 + 5] = inf;
    cloud.log_scales[3 * 5 + 1] = 80.0f;  // absurdly large: clamped
    Renderer renderer(context());
    const SanitizeReport report = renderer.set_scene(cloud);
    EXPECT_EQ(report.dropped(), 3u);
    const RenderOutput out = renderer.render(forward_camera(100, 80, 80.0));
    for (float v : out.rgb) ASSERT_TRUE(std::isfinite(v));
    for (float v : out.depth) ASSERT_TRUE(std::isfinite(v));
}

}  // namespace
}  // namespace vksplat::test
