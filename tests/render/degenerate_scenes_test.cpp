// Scenes at the edges of what floats and the pipeline hold: far from the origin, scales from 1e-10
// to 1e10, 60k Gaussians on one tile (100k off lavapipe), every Gaussian at one depth, the camera inside
// a Gaussian, Gaussians exactly on the near plane. Each must render without NaN or infinity and
// match the reference rasterizer (on the sanitised cloud, which is what the renderer draws) within
// the tolerance stated per case. Each case also prints its time per frame on this device
// ("degenerate: <case> ..."), the table issue 7 asks for; the test does not judge the times, which
// depend on the machine's load.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include "support/gpu_fixture.hpp"
#include "support/image_compare.hpp"
#include "support/scenes.hpp"
#include "vksplat/constants.hpp"
#include "vksplat/reference/rasterizer.hpp"
#include "vksplat/render/renderer.hpp"

namespace vksplat::test {
namespace {

struct Tolerance {
    double max_rgb = 0.01;  // |GPU - reference| per value, as render_vs_reference_test.cpp
    double min_psnr = 90.0;
};

class DegenerateScenes : public GpuTest {
protected:
    // Renders `raw` (sanitised first, as set_scene does) and checks it against the reference.
    void expect_sound(const std::string& name, GaussianCloud cloud, const Camera& camera, Tolerance tolerance = {}) {
        sanitize(cloud);
        Renderer renderer(context());
        renderer.set_scene(cloud);
        const RenderOutput gpu = renderer.render(camera);
        for (size_t i = 0; i < gpu.alpha.size(); ++i) {
            ASSERT_TRUE(std::isfinite(gpu.alpha[i]) && std::isfinite(gpu.depth[i])) << name << ": pixel " << i;
            for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(gpu.rgb[i * 3 + c])) << name << ": pixel " << i;
        }
        constexpr int kFrames = 3;
        const auto start = std::chrono::steady_clock::now();
        for (int i = 0; i < kFrames; ++i) renderer.render_gpu_only(camera);
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() /
                          kFrames;

        const RenderOutput ref = reference::render(cloud, camera, {});
        const ImageDiff rgb = compare(gpu.rgb, ref.rgb);
        const ImageDiff alpha = compare(gpu.alpha, ref.alpha);
        EXPECT_LE(rgb.max_abs, tolerance.max_rgb) << name << ": worst rgb at pixel " << rgb.worst_index / 3;
        EXPECT_LE(alpha.max_abs, tolerance.max_rgb) << name << ": worst alpha at pixel " << alpha.worst_index;
        EXPECT_GE(rgb.psnr, tolerance.min_psnr) << name;
        double covered = 0;
        for (float a : ref.alpha) covered += a > 0.01f;
        std::printf("degenerate: %-22s %7zu Gaussians %4dx%-4d visible %7u  entries %8u  %8.2f ms/frame  "
                    "max |rgb err| %.2e  PSNR %6.1f dB  covered %.0f%%\n",
                    name.c_str(), cloud.size(), camera.width, camera.height, renderer.last_frame().visible,
                    renderer.last_frame().tile_entries, ms, rgb.max_abs, rgb.psnr,
                    100.0 * covered / double(ref.alpha.size()));
        EXPECT_GT(covered, 0) << name << ": the case draws nothing, so it tests nothing";
        RecordProperty("ms_per_frame", std::to_string(ms));
    }
};

// A random cluster of `n` Gaussians within `half` of `centre`.
// `axis_ratio` > 0 draws one size per Gaussian and stretches its axes by up to that factor; 0 draws
// each axis on its own.
GaussianCloud cluster(uint32_t seed, size_t n, glm::dvec3 centre, double half, double scale_min, double scale_max,
                      double axis_ratio = 0) {
    GaussianCloud cloud;
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0), zero_one(0.0, 1.0);
    for (size_t i = 0; i < n; ++i) {
        Splat splat;
        splat.position = centre + half * glm::dvec3(unit(random), unit(random), unit(random));
        const double log_min = std::log(scale_min), log_max = std::log(scale_max);
        const double size = std::exp(log_min + (log_max - log_min) * zero_one(random));
        for (int k = 0; k < 3; ++k)
            splat.scale[k] = axis_ratio > 0 ? size * (1.0 + (axis_ratio - 1.0) * zero_one(random))
                                            : std::exp(log_min + (log_max - log_min) * zero_one(random));
        splat.rotation = glm::normalize(glm::dvec4(unit(random), unit(random), unit(random), unit(random)));
        splat.opacity = 0.2 + 0.7 * zero_one(random);
        splat.color = {zero_one(random), zero_one(random), zero_one(random)};
        add_splat(cloud, splat);
    }
    return cloud;
}

TEST_F(DegenerateScenes, MillionUnitsFromTheOrigin) {
    // Positions are float: at 1e6 a coordinate moves in steps of 1/16. The reference reads the same
    // floats, so what differs is only how each side carries 1e6 through the view transform.
    const glm::dvec3 centre{1e6, -1e6, 1e6};
    const Camera camera = Camera::look_at(centre + glm::dvec3(0, 0, -6), centre, {0, -1, 0}, 96, 80, 90, 90);
    expect_sound("far_from_origin_1e6", cluster(91, 300, centre, 1.5, 0.05, 0.4), camera);
}

TEST_F(DegenerateScenes, ScalesFromTenToTheMinusTenToTenToTheTen) {
    // Each Gaussian's size is drawn log-uniformly from 1e-10 to 1e10 (its three axes within a factor
    // of 2). Sanitising clamps log-scales to [kMinLogScale, kMaxLogScale] (about 1e-10 to 1e6); the
    // largest Gaussians then hold the camera, the smallest are sub-pixel.
    GaussianCloud cloud = cluster(92, 400, {0, 0, 5}, 2.0, 1e-10, 1e10, 2.0);
    for (size_t i = 0; i < cloud.size(); ++i) cloud.opacity_logits[i] = -3.0f;  // keep the view from saturating
    expect_sound("scales_1e-10_to_1e10", cloud, forward_camera(96, 80, 90));
}

TEST_F(DegenerateScenes, ExtremelyAnisotropicScalesStayFinite) {
    // Axes drawn independently from 1e-10 to 1e10: needles and discs with axis ratios up to 1e16,
    // whose 2D covariance is singular to float precision (its determinant cancels catastrophically),
    // so float and double disagree there by design. What must hold is a finite picture; the
    // difference from the reference is printed for the record.
    GaussianCloud cloud = cluster(92, 400, {0, 0, 5}, 2.0, 1e-10, 1e10);
    for (size_t i = 0; i < cloud.size(); ++i) cloud.opacity_logits[i] = -3.0f;
    expect_sound("anisotropic_1e-10_1e10", cloud, forward_camera(96, 80, 90), {.max_rgb = 1e9, .min_psnr = 0});
}

// `n` faint, small Gaussians whose splats all stay within the first 16x16 tile of `camera`: one
// tile list of n entries, deep enough that the last of them still show.
GaussianCloud one_tile(const Camera& camera, int n) {
    GaussianCloud cloud;
    std::mt19937 random(93);
    std::uniform_real_distribution<double> pixel(2.0, 13.0), depth(2.0, 9.0), faint(0.02, 0.1);
    for (int i = 0; i < n; ++i)
        add_splat(cloud, {.position = at_pixel(camera, pixel(random), pixel(random), depth(random)),
                          .scale = glm::dvec3(0.004),
                          .opacity = faint(random),
                          .color = {faint(random) * 10, 0.5, 0.2}});
    return cloud;
}

TEST_F(DegenerateScenes, SixtyThousandGaussiansOnOneTile) {
    const Camera camera = forward_camera(64, 48, 60);
    expect_sound("60k_on_one_tile", one_tile(camera, 60000), camera);
}

// A hundred thousand on one tile: one blend workgroup walks a list of 100k. Not on lavapipe, whose
// llvmpipe backend ends every loop of a shader invocation once all its loops together have gone
// round 65535 times (Mesa gallivm, LP_MAX_TGSI_LOOP_ITERATIONS): the blend then stops about 65030
// entries into the list and the deepest splats are missing (alpha 0.10 short here). 60k, above,
// stays inside that limit.
TEST_F(DegenerateScenes, HundredThousandGaussiansOnOneTile) {
    if (context().info().name.find("llvmpipe") != std::string::npos)
        GTEST_SKIP() << "lavapipe cuts shader loops after 65535 iterations; see the comment above";
    const Camera camera = forward_camera(64, 48, 60);
    expect_sound("100k_on_one_tile", one_tile(camera, 100000), camera);
}

TEST_F(DegenerateScenes, EveryGaussianAtTheSameDepth) {
    // Depth keys all tie: the order is the cloud's, on both sides.
    GaussianCloud cloud = cluster(94, 800, {0, 0, 4}, 1.5, 0.05, 0.3);
    for (size_t i = 0; i < cloud.size(); ++i) cloud.positions[i * 3 + 2] = 4.0f;
    expect_sound("all_at_one_depth", cloud, forward_camera(96, 80, 90));
}

TEST_F(DegenerateScenes, CameraInsideAGaussian) {
    GaussianCloud cloud = cluster(95, 200, {0, 0, 5}, 1.5, 0.05, 0.3);
    // The camera at the origin sits within one sigma of these: one just past the near plane, one
    // well ahead, both far wider than the view.
    add_splat(cloud, {.position = {0.0, 0.0, 0.3}, .scale = {2.0, 2.0, 2.0}, .opacity = 0.3, .color = {0.1, 0.9, 0.3}});
    add_splat(cloud, {.position = {0.2, -0.1, 1.5}, .scale = {3.0, 1.0, 4.0}, .opacity = 0.4, .color = {0.9, 0.1, 0.3}});
    expect_sound("camera_inside_gaussian", cloud, forward_camera(96, 80, 90));
}

TEST_F(DegenerateScenes, GaussiansExactlyOnTheNearPlane) {
    // At the near plane itself (in float, as the cloud stores it) and one float step either side:
    // the cull must decide alike on both sides.
    const float near = constants::kNearPlane;
    GaussianCloud cloud = cluster(96, 100, {0, 0, 5}, 1.5, 0.05, 0.3);
    int i = 0;
    for (float z : {std::nextafter(near, 0.0f), near, std::nextafter(near, 1.0f)})
        for (double x : {-0.05, 0.0, 0.05})
            add_splat(cloud, {.position = {x + 0.01 * i++, 0.02, z}, .scale = {0.01, 0.01, 0.01}, .opacity = 0.6});
    expect_sound("on_the_near_plane", cloud, forward_camera(96, 80, 90));
}

}  // namespace
}  // namespace vksplat::test
