// Per-Gaussian statistics from the blend pass, against the reference and on scenes where the
// answer is known.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "support/gpu_fixture.hpp"
#include "support/scenes.hpp"
#include "vksplat/reference/rasterizer.hpp"
#include "vksplat/render/renderer.hpp"

namespace vksplat::test {
namespace {

class Stats : public GpuTest {
protected:
    RenderSettings with_stats() const {
        RenderSettings settings;
        settings.gather_stats = true;
        return settings;
    }
};

TEST_F(Stats, MatchTheReference) {
    const GaussianCloud cloud = random_scene(31, 600, 2);
    const Camera camera = forward_camera(160, 120, 120.0);
    Renderer renderer(context());
    renderer.set_scene(cloud);
    const GaussianStats gpu = renderer.render(camera, with_stats()).stats;
    const GaussianStats ref = reference::render(cloud, camera, with_stats()).stats;
    ASSERT_EQ(gpu.size(), cloud.size());
    size_t same_pixels = 0, visible = 0;
    for (size_t i = 0; i < cloud.size(); ++i) {
        ASSERT_EQ(gpu.visible[i], ref.visible[i]) << i;
        if (!ref.visible[i]) {
            EXPECT_EQ(gpu.pixels[i], 0u);
            continue;
        }
        ++visible;
        EXPECT_NEAR(gpu.screen_x[i], ref.screen_x[i], 1e-3) << i;
        EXPECT_NEAR(gpu.screen_y[i], ref.screen_y[i], 1e-3) << i;
        EXPECT_NEAR(gpu.depth[i], ref.depth[i], 1e-5 * ref.depth[i]) << i;
        EXPECT_EQ(gpu.radius[i], ref.radius[i]) << i;
        // A borderline alpha = 1/255 flips a pixel at most; weights agree to float rounding.
        EXPECT_NEAR(double(gpu.pixels[i]), double(ref.pixels[i]), 2.0 + 1e-3 * ref.pixels[i]) << i;
        same_pixels += gpu.pixels[i] == ref.pixels[i];
        EXPECT_NEAR(gpu.blend_weight[i], ref.blend_weight[i], 1e-4 + 1e-4 * ref.blend_weight[i]) << i;
        EXPECT_NEAR(gpu.max_weight[i], ref.max_weight[i], 1e-5) << i;
        // Which pixel holds the centre may differ where float and double round a centre that
        // lies on a pixel border; elsewhere the centre weights agree.
        const auto near_border = [](double x) { return std::abs(x - std::floor(x) - 0.5) < 1e-3; };
        if (!near_border(ref.screen_x[i]) && !near_border(ref.screen_y[i])) {
            EXPECT_NEAR(gpu.centre_weight[i], ref.centre_weight[i], 1e-5) << i;
        }
    }
    EXPECT_GT(visible, 300u);
    EXPECT_GE(double(same_pixels), 0.98 * double(visible));
}

TEST_F(Stats, HiddenBehindAnOpaqueWallScoresZero) {
    GaussianCloud cloud;
    // Four layers of flat, wide, 0.99-opaque splats: alpha >= 0.93 over the whole view, and
    // 0.07^4 < 1e-4, so every pixel stops before reaching what lies behind.
    for (double z : {2.0, 2.1, 2.2, 2.3}) add_splat(cloud, {.position = {0, 0, z}, .scale = {3, 3, 0.01}, .opacity = 0.99});
    add_splat(cloud, {.position = {0.1, 0.0, 5.0}, .scale = {0.2, 0.2, 0.2}, .opacity = 0.9});
    add_splat(cloud, {.position = {50.0, 0.0, 5.0}, .scale = {0.2, 0.2, 0.2}, .opacity = 0.9});  // far off screen

    Renderer renderer(context());
    renderer.set_scene(cloud);
    const GaussianStats stats = renderer.render(forward_camera(64, 64, 64.0), with_stats()).stats;
    EXPECT_GT(stats.blend_weight[0], 100.0);
    EXPECT_GT(stats.pixels[3], 0u) << "the last layer stops what the first three left";
    EXPECT_EQ(stats.visible[4], 1u);
    EXPECT_EQ(stats.blend_weight[4], 0.0);
    EXPECT_EQ(stats.pixels[4], 0u);
    EXPECT_EQ(stats.visible[5], 0u);
    EXPECT_EQ(stats.pixels[5], 0u);
}

TEST_F(Stats, DroppingGaussiansThatTouchNoPixelIsLossless) {
    GaussianCloud cloud = random_scene(32, 800, 3, 2.0f, 8.0f, 0.005f, 0.3f, 4.0f);
    const GaussianCloud far = random_scene(33, 100, 3, -5.0f, -1.0f);  // behind the camera
    for (size_t i = 0; i < far.size(); ++i) cloud.append(far, i);
    const std::vector<Camera> cameras = {forward_camera(120, 90, 100.0), forward_camera(90, 120, 140.0)};

    Renderer renderer(context());
    renderer.set_scene(cloud);
    std::vector<uint8_t> keep(cloud.size(), 0);
    std::vector<RenderOutput> before;
    for (const Camera& camera : cameras) {
        before.push_back(renderer.render(camera, with_stats()));
        for (size_t i = 0; i < cloud.size(); ++i) keep[i] |= before.back().stats.pixels[i] > 0;
    }
    const GaussianCloud kept = cloud.subset(keep);
    ASSERT_LT(kept.size(), cloud.size() - 100) << "some Gaussians must be droppable";
    renderer.set_scene(kept);
    for (size_t v = 0; v < cameras.size(); ++v) {
        const RenderOutput after = renderer.render(cameras[v]);
        EXPECT_EQ(after.rgb, before[v].rgb) << "view " << v;
        EXPECT_EQ(after.alpha, before[v].alpha) << "view " << v;
        EXPECT_EQ(after.depth, before[v].depth) << "view " << v;
    }
}

TEST_F(Stats, AskingForStatsChangesNoPixelAndIsDeterministic) {
    Renderer renderer(context());
    renderer.set_scene(random_scene(34, 1000, 1));
    const Camera camera = forward_camera(128, 96, 100.0);
    const RenderOutput plain = renderer.render(camera);
    EXPECT_EQ(plain.stats.size(), 0u);
    const RenderOutput a = renderer.render(camera, with_stats());
    const RenderOutput b = renderer.render(camera, with_stats());
    EXPECT_EQ(plain.rgb, a.rgb);
    EXPECT_EQ(a.stats.blend_weight, b.stats.blend_weight);
    EXPECT_EQ(a.stats.max_weight, b.stats.max_weight);
    EXPECT_EQ(a.stats.pixels, b.stats.pixels);
}

TEST_F(Stats, IndexedLikeTheInputWhenSanitisingDrops) {
    GaussianCloud cloud = random_scene(35, 50, 0);
    cloud.positions[3 * 10] = std::numeric_limits<float>::quiet_NaN();
    Renderer renderer(context());
    renderer.set_scene(cloud);
    const GaussianStats stats = renderer.render(forward_camera(64, 64, 60.0), with_stats()).stats;
    ASSERT_EQ(stats.size(), 50u);
    EXPECT_EQ(stats.visible[10], 0u);
    GaussianCloud clean = cloud;
    clean.positions[3 * 10] = 1000.0f;  // same scene with Gaussian 10 off screen instead
    const GaussianStats ref = reference::render(clean, forward_camera(64, 64, 60.0), with_stats()).stats;
    for (size_t i = 0; i < 50; ++i) {
        if (i == 10) continue;
        EXPECT_EQ(stats.visible[i], ref.visible[i]) << i;
        EXPECT_NEAR(stats.blend_weight[i], ref.blend_weight[i], 1e-3) << i;
    }
}

// Each field the same bytes (not just ==, which would let -0 stand for 0).
template <typename T>
void expect_same_bytes(const std::vector<T>& a, const std::vector<T>& b, const char* field, size_t view) {
    ASSERT_EQ(a.size(), b.size()) << field << ", view " << view;
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(T)), 0) << field << ", view " << view;
}

TEST_F(Stats, StatsAloneAreRendersStatsByteForByte) {
    // Gaussians in view, behind the cameras and far off to the side (culled, never blended).
    GaussianCloud cloud = random_scene(36, 700, 2);
    for (const GaussianCloud& extra : {random_scene(37, 60, 2, -5.0f, -1.0f), random_scene(38, 60, 2, 40.0f, 60.0f)})
        for (size_t i = 0; i < extra.size(); ++i) cloud.append(extra, i);
    for (size_t i = cloud.size() - 60; i < cloud.size(); ++i) cloud.positions[3 * i] += 500.0f;
    const std::vector<Camera> cameras = {
        forward_camera(96, 72, 80.0),
        Camera::look_at({2.0, -0.5, 0.0}, {0.0, 0.0, 5.0}, {0.0, -1.0, 0.0}, 64, 80, 60.0, 60.0),
        Camera::look_at({0.0, 0.0, 9.0}, {0.0, 0.0, 5.0}, {0.0, -1.0, 0.0}, 80, 64, 70.0, 70.0)};  // looks back
    Renderer renderer(context());
    renderer.set_scene(cloud);
    for (size_t v = 0; v < cameras.size(); ++v) {
        // Stats alone first: were the statistics left from the previous frame, they would be its view's.
        const GaussianStats alone = renderer.render_stats(cameras[v]);
        const GaussianStats rendered = renderer.render(cameras[v], with_stats()).stats;
        ASSERT_EQ(alone.size(), cloud.size());
        expect_same_bytes(alone.visible, rendered.visible, "visible", v);
        expect_same_bytes(alone.screen_x, rendered.screen_x, "screen_x", v);
        expect_same_bytes(alone.screen_y, rendered.screen_y, "screen_y", v);
        expect_same_bytes(alone.depth, rendered.depth, "depth", v);
        expect_same_bytes(alone.radius, rendered.radius, "radius", v);
        expect_same_bytes(alone.blend_weight, rendered.blend_weight, "blend_weight", v);
        expect_same_bytes(alone.max_weight, rendered.max_weight, "max_weight", v);
        expect_same_bytes(alone.pixels, rendered.pixels, "pixels", v);
        expect_same_bytes(alone.centre_weight, rendered.centre_weight, "centre_weight", v);
        // The comparison covers blended, culled and never-projected Gaussians.
        size_t blended = 0, hidden = 0;
        for (size_t i = 0; i < cloud.size(); ++i) {
            blended += alone.blend_weight[i] > 0.0;
            hidden += !alone.visible[i];
        }
        EXPECT_GT(blended, 100u) << "view " << v;
        EXPECT_GE(hidden, 60u) << "view " << v;
    }
}

}  // namespace
}  // namespace vksplat::test
