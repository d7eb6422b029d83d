// The GPU renderer against the double-precision reference rasterizer on generated scenes that
// cover the edge cases. Tolerances, held at every pixel:
//   rgb, alpha:   |GPU - reference| <= 0.01 everywhere, and PSNR >= 90 dB over the image.
//                 Float against double agrees to ~1e-5 (PSNR 130+ dB), except where it flips a
//                 borderline decision — alpha at exactly 1/255, a 3-sigma rectangle touching a
//                 tile, the 1e-4 transmittance stop — which moves one splat's share of one pixel
//                 (the worst seen: 0.0015, on the 333x777 scene).
//   depth:        |GPU - reference| <= 0.02 * depth where alpha > 0.05.
//   contributors: equal on >= 99% of pixels.
#include <gtest/gtest.h>

#include <cmath>

#include "support/gpu_fixture.hpp"
#include "support/image_compare.hpp"
#include "support/scenes.hpp"
#include "vksplat/reference/rasterizer.hpp"
#include "vksplat/render/renderer.hpp"

namespace vksplat::test {
namespace {

constexpr double kMaxColorError = 0.01;
constexpr double kMinPsnr = 90.0;

class RenderVsReference : public GpuTest {
protected:
    void expect_match(const GaussianCloud& cloud, const Camera& camera, const RenderSettings& settings = {}) {
        Renderer renderer(context());
        renderer.set_scene(cloud);
        const RenderOutput gpu = renderer.render(camera, settings);
        const RenderOutput ref = reference::render(cloud, camera, settings);
        ASSERT_EQ(gpu.rgb.size(), ref.rgb.size());

        const ImageDiff rgb = compare(gpu.rgb, ref.rgb);
        EXPECT_LE(rgb.max_abs, kMaxColorError) << "worst rgb value at pixel " << rgb.worst_index / 3;
        EXPECT_GE(rgb.psnr, kMinPsnr);
        const ImageDiff alpha = compare(gpu.alpha, ref.alpha);
        EXPECT_LE(alpha.max_abs, kMaxColorError) << "worst alpha at pixel " << alpha.worst_index;
        EXPECT_GE(alpha.psnr, kMinPsnr);

        size_t same_contributors = 0;
        for (size_t i = 0; i < gpu.depth.size(); ++i) {
            for (int c = 0; c < 3; ++c) ASSERT_FALSE(std::isnan(gpu.rgb[i * 3 + c])) << "NaN at pixel " << i;
            if (ref.alpha[i] > 0.05f) {
                EXPECT_NEAR(gpu.depth[i], ref.depth[i], 0.02 * std::abs(ref.depth[i]) + 1e-4) << "depth at " << i;
            }
            same_contributors += gpu.contributors[i] == ref.contributors[i];
        }
        EXPECT_GE(double(same_contributors), 0.99 * double(gpu.depth.size()));
        worst_error = rgb.max_abs;
        psnr = rgb.psnr;
        RecordProperty("max_rgb_error", std::to_string(rgb.max_abs));
        RecordProperty("psnr", std::to_string(rgb.psnr));
    }
    double worst_error = 0, psnr = 0;
};

TEST_F(RenderVsReference, RandomScenesAtEverySHDegree) {
    for (int degree = 0; degree <= 3; ++degree) {
        SCOPED_TRACE("SH degree " + std::to_string(degree));
        expect_match(random_scene(10 + degree, 400, degree), forward_camera(160, 120, 120.0));
    }
}

TEST_F(RenderVsReference, ShDegreeCapBelowTheScenes) {
    RenderSettings settings;
    settings.max_sh_degree = 1;
    expect_match(random_scene(3, 300, 3), forward_camera(96, 64, 80.0), settings);
}

TEST_F(RenderVsReference, LookAtCameraAndBackground) {
    const Camera camera = Camera::look_at({3.0, -4.0, 2.0}, {0.0, 0.0, 5.0}, {0.0, -1.0, 0.0}, 128, 128, 110.0, 110.0);
    RenderSettings settings;
    settings.background = {0.2f, 0.5f, 1.0f};
    expect_match(random_scene(4, 500, 2), camera, settings);
}

TEST_F(RenderVsReference, TinyGaussians) {
    expect_match(random_scene(5, 300, 1, 2.0f, 6.0f, 1e-6f, 2e-6f), forward_camera(96, 96, 100.0));
}

TEST_F(RenderVsReference, HugeGaussians) {
    GaussianCloud cloud = random_scene(6, 60, 1, 2.0f, 8.0f, 0.01f, 0.1f);
    const GaussianCloud huge = random_scene(7, 6, 1, 1.0f, 3.0f, 2.0f, 8.0f);
    for (size_t i = 0; i < huge.size(); ++i) cloud.append(huge, i);
    expect_match(cloud, forward_camera(128, 96, 100.0));
}

// Splats over more than 128 tiles are emitted by their whole subgroup (emit_tile_entries.comp),
// beside small ones emitted one per invocation: 25x19 tiles, a few splats over most of them.
TEST_F(RenderVsReference, HugeGaussiansOverHundredsOfTiles) {
    GaussianCloud cloud = random_scene(16, 200, 1, 2.0f, 8.0f, 0.01f, 0.1f);
    const GaussianCloud huge = random_scene(17, 8, 1, 3.0f, 6.0f, 1.0f, 3.0f);
    for (size_t i = 0; i < huge.size(); ++i) cloud.append(huge, i);
    expect_match(cloud, forward_camera(400, 300, 300.0));
}

TEST_F(RenderVsReference, BehindAndStraddlingTheNearPlane) {
    GaussianCloud cloud;
    const double depths[] = {-2.0, -0.1, 0.0, 0.1, 0.19, 0.2, 0.21, 0.3, 0.5, 1.0};
    int k = 0;
    for (double z : depths) {
        add_splat(cloud, {.position = {0.05 * (k % 3 - 1), 0.04 * (k % 2), z},
                          .scale = {0.3, 0.2, 0.5},  // large enough to straddle z = 0.2
                          .opacity = 0.6,
                          .color = {0.9, 0.4, 0.1}});
        ++k;
    }
    expect_match(cloud, forward_camera(96, 80, 60.0));
}

TEST_F(RenderVsReference, GaussiansOnTileBorders) {
    GaussianCloud cloud;
    const Camera camera = forward_camera(64, 64, 64.0);
    int k = 0;
    // Centres at pixel coordinates on and around the tile borders 16, 32, 48.
    for (double u : {15.0, 15.5, 16.0, 31.5, 32.0, 47.9}) {
        for (double v : {15.5, 16.0, 32.0, 48.1}) {
            add_splat(cloud, {.position = at_pixel(camera, u, v, 4.0 + 0.01 * k),
                              .scale = {0.02 + 0.01 * (k % 4), 0.03, 0.02},
                              .opacity = 0.8,
                              .color = {(k % 3) * 0.4, (k % 5) * 0.2, 0.5}});
            ++k;
        }
    }
    expect_match(cloud, camera);
}

TEST_F(RenderVsReference, OddImageSize) { expect_match(random_scene(8, 500, 2), forward_camera(333, 777, 300.0)); }

TEST_F(RenderVsReference, OffCentrePrincipalPoint) {
    Camera camera = forward_camera(160, 120, 110.0);
    camera.cx = 0.3 * camera.width;
    camera.cy = 0.72 * camera.height;
    expect_match(random_scene(9, 400, 3), camera);
}

TEST_F(RenderVsReference, OpaqueStackStopsAtTheTransmittanceFloor) {
    GaussianCloud cloud;
    for (int k = 0; k < 40; ++k) {
        // Inserted far to near, so the sort has work to do.
        add_splat(cloud, {.position = {0.01 * (k % 3), -0.01 * (k % 2), 10.0 - 0.2 * k},
                          .scale = {0.4, 0.4, 0.05},
                          .opacity = 0.99,
                          .color = {double(k % 2), (k % 3) * 0.5, 0.25}});
    }
    expect_match(cloud, forward_camera(64, 64, 64.0));
}

TEST_F(RenderVsReference, SingleGaussian) {
    GaussianCloud cloud;
    add_splat(cloud, {.position = {0.1, -0.05, 3.0},
                      .scale = {0.2, 0.1, 0.05},
                      .rotation = {0.9, 0.1, 0.3, -0.2},
                      .opacity = 0.7,
                      .color = {0.2, 0.7, 0.9}});
    expect_match(cloud, forward_camera(80, 60, 70.0));
}

TEST_F(RenderVsReference, EmptyViewShowsTheBackground) {
    const GaussianCloud behind = random_scene(11, 100, 1, -8.0f, -1.0f);
    const GaussianCloud empty;
    RenderSettings settings;
    settings.background = {0.25f, 0.5f, 0.75f};
    Renderer renderer(context());
    for (const GaussianCloud* cloud : {&behind, &empty}) {
        renderer.set_scene(*cloud);
        const RenderOutput out = renderer.render(forward_camera(40, 30, 40.0), settings);
        for (size_t i = 0; i < out.alpha.size(); ++i) {
            ASSERT_EQ(out.alpha[i], 0.0f);
            ASSERT_EQ(out.depth[i], 0.0f);
            for (int c = 0; c < 3; ++c) ASSERT_EQ(out.rgb[i * 3 + c], settings.background[c]);
        }
        EXPECT_EQ(renderer.last_frame().visible, 0u);
    }
}

}  // namespace
}  // namespace vksplat::test
