// Frames larger than the memory budget, rendered in depth-ordered chunks that carry each pixel's
// state: they must give the unchunked picture. Chunking changes nothing in the arithmetic of any
// pixel (the same splats, in the same order, through the same float operations; the carried
// colour, transmittance, depth sum and count are stored as they are, not re-derived), so the
// expected difference is zero. Only two splats whose depths agree to within float rounding on
// either side of a chunk boundary could swap (scene_chunks.hpp); the generated scenes have none
// such, hence the exact comparisons; lego is compared by PSNR and max error to allow for them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/frame_resources.hpp"
#include "render/gpu_scene.hpp"
#include "support/gpu_fixture.hpp"
#include "support/image_compare.hpp"
#include "support/scenes.hpp"
#include "support/test_data.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/cameras.hpp"
#include "vksplat/io/ply.hpp"
#include "vksplat/render/renderer.hpp"

namespace vksplat::test {
namespace {

class ChunkedRender : public GpuTest {
protected:
    // A budget whose chunks hold at most `chunk` Gaussians of an SH-`degree` scene in this view
    // (with the renderer's first guess of 4 tile entries per Gaussian). It must be below what the
    // whole scene of `n` needs, which the per-pixel buffers (24 bytes a pixel more when chunked)
    // could otherwise outweigh; hence the small images below.
    static uint64_t budget_for_chunk(uint32_t chunk, uint32_t n, int degree, const Camera& camera) {
        const uint32_t pixels = uint32_t(camera.width * camera.height);
        const uint32_t tiles = uint32_t(((camera.width + 15) / 16) * ((camera.height + 15) / 16));
        const uint64_t budget = render::GpuScene::bytes_for(chunk, degree, false) +
                                render::FrameResources::bytes_for(context(), chunk, chunk * 4, pixels, tiles, true);
        const uint64_t whole = render::GpuScene::bytes_for(n, degree, false) +
                               render::FrameResources::bytes_for(context(), n, n * 4, pixels, tiles, false);
        EXPECT_LT(budget, whole) << "the test's budget would not force chunks";
        return budget;
    }
    static RenderOutput render_with(const GaussianCloud& cloud, const Camera& camera, const RenderSettings& settings,
                                    uint64_t budget, FrameStats* stats = nullptr) {
        Renderer renderer(context());
        renderer.set_scene(cloud, SceneStorage{.memory_budget = budget});
        RenderOutput out = renderer.render(camera, settings);
        if (stats) *stats = renderer.last_frame();
        return out;
    }
};

void expect_same_picture(const RenderOutput& whole, const RenderOutput& chunked) {
    EXPECT_EQ(whole.rgb, chunked.rgb);
    EXPECT_EQ(whole.alpha, chunked.alpha);
    EXPECT_EQ(whole.depth, chunked.depth);
    EXPECT_EQ(whole.contributors, chunked.contributors);
}

// Every per-Gaussian statistic equal but the blend weight, which may differ by `blend_tolerance`
// relative (chunks add a Gaussian's weights in another order).
void expect_same_stats(const GaussianStats& a, const GaussianStats& b, double blend_tolerance) {
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(a.visible, b.visible);
    EXPECT_EQ(a.screen_x, b.screen_x);
    EXPECT_EQ(a.screen_y, b.screen_y);
    EXPECT_EQ(a.depth, b.depth);
    EXPECT_EQ(a.radius, b.radius);
    for (size_t i = 0; i < a.size(); ++i)
        ASSERT_NEAR(a.blend_weight[i], b.blend_weight[i], blend_tolerance * a.blend_weight[i] + (blend_tolerance > 0 ? 1e-9 : 0))
            << "Gaussian " << i;
    EXPECT_EQ(a.max_weight, b.max_weight);
    EXPECT_EQ(a.pixels, b.pixels);
    EXPECT_EQ(a.centre_weight, b.centre_weight);
}

TEST_F(ChunkedRender, MatchesTheWholeFrameIn2And3AndManyChunks) {
    const GaussianCloud cloud = random_scene(31, 2000, 3);
    const Camera camera = forward_camera(96, 72, 70.0);
    RenderSettings settings;
    settings.background = {0.2f, 0.4f, 0.6f};  // added once, after the last chunk
    FrameStats whole_stats;
    const RenderOutput whole = render_with(cloud, camera, settings, 0, &whole_stats);
    ASSERT_EQ(whole_stats.chunks, 1u);
    for (const uint32_t chunks : {2u, 3u, 25u}) {
        SCOPED_TRACE("chunks " + std::to_string(chunks));
        const uint64_t budget = budget_for_chunk((2000 + chunks - 1) / chunks, 2000, 3, camera);
        FrameStats stats;
        const RenderOutput chunked = render_with(cloud, camera, settings, budget, &stats);
        EXPECT_GE(stats.chunks, chunks);  // more where a chunk's tile entries overflowed and it was split
        EXPECT_LE(stats.device_bytes, budget);
        EXPECT_EQ(stats.visible, whole_stats.visible);
        expect_same_picture(whole, chunked);
    }
}

TEST_F(ChunkedRender, PixelsThatStopInTheFirstChunkStayStopped) {
    // In front, three flat splats over the image centre: alpha 0.98 (T = 0.02), 0.99 (T = 2e-4),
    // then 0.99, which would take T below 1e-4 and so stops the pixel with T = 2e-4. Behind, in
    // later chunks, faint splats with alpha 0.3 that a resumed pixel would still blend
    // (2e-4 * 0.7 >= 1e-4).
    const Camera camera = forward_camera(32, 32, 40.0);
    GaussianCloud cloud;
    cloud.sh_degree = 0;
    const double opacities[3] = {0.98, 0.99, 0.99};
    for (int k = 0; k < 3; ++k)
        add_splat(cloud, {.position = at_pixel(camera, 16, 16, 2.0 + 0.01 * k), .scale = glm::dvec3(3.0, 3.0, 0.01),
                          .opacity = opacities[k], .color = {1.0, 0.2 * k, 0.0}});
    for (int k = 0; k < 1000; ++k)
        add_splat(cloud, {.position = at_pixel(camera, 16, 16, 5.0 + 0.001 * k), .scale = glm::dvec3(3.0, 3.0, 0.01),
                          .opacity = 0.3, .color = {0.0, 1.0, 1.0}});
    const RenderOutput whole = render_with(cloud, camera, {}, 0);
    const size_t centre = 16 * 32 + 16;
    ASSERT_EQ(whole.contributors[centre], 2u) << "the scene should stop the centre pixel at the third splat";
    FrameStats stats;
    const RenderOutput chunked = render_with(cloud, camera, {}, budget_for_chunk(200, 1003, 0, camera), &stats);
    EXPECT_GE(stats.chunks, 5u);
    EXPECT_EQ(chunked.contributors[centre], 2u);
    expect_same_picture(whole, chunked);
}

TEST_F(ChunkedRender, AChunkBoundaryBetweenEqualDepthsKeepsTheWholeFramesOrder) {
    // Every splat at exactly depth 4 (the forward camera computes it without rounding), so the
    // depth sort orders them by index alone and each chunk boundary falls between equal depths.
    const Camera camera = forward_camera(48, 48, 50.0);
    GaussianCloud cloud;
    cloud.sh_degree = 0;
    for (int k = 0; k < 900; ++k) {
        const double u = 8 + (k * 7) % 32, v = 8 + (k * 11) % 32;
        add_splat(cloud, {.position = at_pixel(camera, u, v, 4.0), .scale = glm::dvec3(0.1, 0.07, 0.01),
                          .opacity = 0.6, .color = {(k % 3) / 2.0, (k % 5) / 4.0, (k % 7) / 6.0}});
    }
    const RenderOutput whole = render_with(cloud, camera, {}, 0);
    for (const uint32_t chunk : {450u, 301u, 70u}) {
        SCOPED_TRACE("chunk " + std::to_string(chunk));
        FrameStats stats;
        const RenderOutput chunked = render_with(cloud, camera, {}, budget_for_chunk(chunk, 900, 0, camera), &stats);
        EXPECT_GE(stats.chunks, (900 + chunk - 1) / chunk);
        expect_same_picture(whole, chunked);
    }
}

TEST_F(ChunkedRender, ChunksWhoseTileEntriesOverflowAreRedrawnOrSplit) {
    // Large splats touch far more tiles than the first guess of 4 per Gaussian.
    const GaussianCloud cloud = random_scene(22, 3000, 0, 2.0f, 3.0f, 0.5f, 1.0f);
    const Camera camera = forward_camera(64, 64, 50.0);
    const RenderOutput whole = render_with(cloud, camera, {}, 0);
    const uint64_t budget = budget_for_chunk(1500, 3000, 0, camera);
    FrameStats stats;
    const RenderOutput chunked = render_with(cloud, camera, {}, budget, &stats);
    EXPECT_GT(stats.attempts, 1u);
    EXPECT_GT(stats.chunks, 2u) << "no room to grow the entries: the chunks must have been split";
    EXPECT_LE(stats.device_bytes, budget);
    expect_same_picture(whole, chunked);
}

TEST_F(ChunkedRender, IsDeterministic) {
    const GaussianCloud cloud = random_scene(32, 1500, 2);
    const Camera camera = forward_camera(64, 48, 50.0);
    const uint64_t budget = budget_for_chunk(400, 1500, 2, camera);
    Renderer renderer(context());
    renderer.set_scene(cloud, SceneStorage{.memory_budget = budget});
    const RenderOutput a = renderer.render(camera);
    const RenderOutput b = renderer.render(camera);
    EXPECT_GE(renderer.last_frame().chunks, 4u);
    expect_same_picture(a, b);
    expect_same_picture(a, render_with(cloud, camera, {}, budget));
}

TEST_F(ChunkedRender, HalfPrecisionShChunksMatchTheWholeFrame) {
    const GaussianCloud cloud = random_scene(33, 801, 1);  // odd SH value count per chunk edge cases
    const Camera camera = forward_camera(48, 48, 40.0);
    Renderer whole(context()), chunked(context());
    whole.set_scene(cloud, SceneStorage{.half_sh = true});
    chunked.set_scene(cloud, SceneStorage{.half_sh = true, .memory_budget = budget_for_chunk(201, 801, 1, camera)});
    expect_same_picture(whole.render(camera), chunked.render(camera));
    EXPECT_GE(chunked.last_frame().chunks, 4u);
}

TEST_F(ChunkedRender, AViewWithNothingInFrontIsTheBackground) {
    GaussianCloud cloud = random_scene(37, 3000, 0);
    for (size_t i = 0; i < cloud.size(); ++i) cloud.positions[3 * i + 2] *= -1.0f;  // all behind the camera
    const Camera camera = forward_camera(32, 32, 30.0);
    RenderSettings settings;
    settings.background = {0.25f, 0.5f, 0.75f};
    FrameStats stats;
    const RenderOutput whole = render_with(cloud, camera, settings, 0);
    const RenderOutput chunked =
        render_with(cloud, camera, settings, budget_for_chunk(500, 3000, 0, camera), &stats);
    EXPECT_EQ(stats.visible, 0u);
    EXPECT_EQ(chunked.rgb[0], 0.25f);
    expect_same_picture(whole, chunked);
}

TEST_F(ChunkedRender, ABudgetTooSmallForOneChunkIsAClearError) {
    Renderer renderer(context());
    renderer.set_scene(random_scene(34, 100, 0), SceneStorage{.memory_budget = 4096});
    try {
        renderer.render(forward_camera(64, 64, 60.0));
        FAIL() << "expected a GpuError";
    } catch (const GpuError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("memory budget of"), std::string::npos) << message;
        EXPECT_NE(message.find("too small"), std::string::npos) << message;
        EXPECT_NE(message.find("--memory-budget"), std::string::npos) << message;
    }
}

TEST_F(ChunkedRender, PerGaussianStatisticsMatchTheWholeFrames) {
    // Each Gaussian blends within one chunk, against the same transmittance as in the whole frame:
    // the statistics are the same numbers. Only the blend weight is summed in float within a
    // subgroup before its fixed-point atomic (blend_body.glsl), so where a device groups the active
    // pixels differently in the two frames it may differ by float rounding (lavapipe: exactly equal).
    if (!context().info().int64_atomics) GTEST_SKIP() << "no 64-bit atomics on " << context().info().name;
    const Camera camera = forward_camera(32, 32, 30.0);
    GaussianCloud cloud = random_scene(35, 2000, 1);
    cloud.positions[2] = -1.0f;  // one behind the camera: in no chunk, not visible
    RenderSettings settings;
    settings.gather_stats = true;
    const RenderOutput whole = render_with(cloud, camera, settings, 0);
    FrameStats stats;
    const RenderOutput chunked = render_with(cloud, camera, settings, budget_for_chunk(500, 2000, 1, camera), &stats);
    EXPECT_GE(stats.chunks, 4u);
    expect_same_picture(whole, chunked);
    const GaussianStats& b = chunked.stats;
    ASSERT_EQ(b.size(), cloud.size());
    EXPECT_EQ(b.visible[0], 0);
    expect_same_stats(whole.stats, b, 1e-5);
    size_t contributing = 0;
    for (double w : b.blend_weight) contributing += w > 0.0;
    EXPECT_GT(contributing, 500u) << "the comparison should cover Gaussians of every chunk";
}

TEST_F(ChunkedRender, StatsAloneAreTheChunkedRendersStats) {
    // render_stats reads back no picture, also from chunks; each chunk's statistics still come back.
    if (!context().info().int64_atomics) GTEST_SKIP() << "no 64-bit atomics on " << context().info().name;
    const Camera camera = forward_camera(32, 32, 30.0);
    GaussianCloud cloud = random_scene(36, 2000, 1);
    cloud.positions[2] = -1.0f;  // one behind the camera
    Renderer renderer(context());
    renderer.set_scene(cloud, SceneStorage{.memory_budget = budget_for_chunk(500, 2000, 1, camera)});
    const GaussianStats alone = renderer.render_stats(camera);
    EXPECT_GE(renderer.last_frame().chunks, 4u);
    RenderSettings settings;
    settings.gather_stats = true;
    const GaussianStats rendered = renderer.render(camera, settings).stats;
    ASSERT_EQ(alone.size(), cloud.size());
    EXPECT_EQ(alone.visible[0], 0);
    expect_same_stats(alone, rendered, 0.0);
    size_t contributing = 0;
    for (double w : alone.blend_weight) contributing += w > 0.0;
    EXPECT_GT(contributing, 500u) << "the comparison should cover Gaussians of every chunk";
}

TEST_F(ChunkedRender, RecordingNeedsTheWholeScene) {
    const Camera camera = forward_camera(32, 32, 30.0);
    Renderer renderer(context());
    renderer.set_scene(random_scene(35, 2000, 0),
                       SceneStorage{.memory_budget = budget_for_chunk(500, 2000, 0, camera)});
    // A handle that is never used: record() refuses before it records anything.
    const auto target = RenderTarget::to_buffer(reinterpret_cast<VkBuffer>(uintptr_t(1)), VK_FORMAT_R8G8B8A8_UNORM);
    try {
        renderer.record(VK_NULL_HANDLE, camera, {}, target);
        FAIL() << "expected a GpuError";
    } catch (const GpuError& e) {
        EXPECT_NE(std::string(e.what()).find("cannot be split into chunks"), std::string::npos) << e.what();
    }
    renderer.render(camera);  // still renders through render()
    EXPECT_GE(renderer.last_frame().chunks, 4u);
}

TEST_F(ChunkedRender, ABudgetThatFitsRendersWhole) {
    const GaussianCloud cloud = random_scene(36, 500, 1);
    const Camera camera = forward_camera(96, 96, 80.0);
    FrameStats stats;
    const RenderOutput whole = render_with(cloud, camera, {}, 0);
    const RenderOutput budgeted = render_with(cloud, camera, {}, 64ull << 20, &stats);
    EXPECT_EQ(stats.chunks, 1u);
    EXPECT_LE(stats.device_bytes, 64ull << 20);
    expect_same_picture(whole, budgeted);
}

TEST_F(ChunkedRender, LegoInChunksMatchesTheWholeFrame) {
    VKSPLAT_REQUIRE_SHARED_DATA();
    const auto dir = shared_data_dir() / "lego";
    const GaussianCloud cloud = io::read_ply(dir / "point_cloud.ply");
    const Camera camera = io::read_cameras(dir / "cameras.json")[0];
    RenderSettings settings;
    settings.background = {1.0f, 1.0f, 1.0f};
    FrameStats whole_stats, stats;
    const RenderOutput whole = render_with(cloud, camera, settings, 0, &whole_stats);
    const uint64_t budget = whole_stats.device_bytes / 2;
    const RenderOutput chunked = render_with(cloud, camera, settings, budget, &stats);
    const ImageDiff diff = compare(whole.rgb, chunked.rgb);
    std::printf("[chunked] lego view 0: %u chunks, %.1f of %.1f MiB, PSNR %.2f dB, max error %.3g\n", stats.chunks,
                stats.device_bytes / 1048576.0, whole_stats.device_bytes / 1048576.0, diff.psnr, diff.max_abs);
    EXPECT_GE(stats.chunks, 2u);
    EXPECT_LE(stats.device_bytes, budget);
    EXPECT_TRUE(diff.psnr >= 90.0 || diff.max_abs <= 1e-5) << "PSNR " << diff.psnr << ", max " << diff.max_abs;
    EXPECT_LE(compare(whole.alpha, chunked.alpha).max_abs, 1e-5);
}

}  // namespace
}  // namespace vksplat::test
