// reference::render: blending, ordering, early stop, background and image geometry.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "support/scenes.hpp"
#include "vksplat/constants.hpp"
#include "vksplat/error.hpp"
#include "vksplat/reference/rasterizer.hpp"

namespace vksplat::reference {
namespace {

using namespace vksplat::constants;
using test::add_splat;
using test::at_pixel;
using test::forward_camera;
using test::Splat;

// 65 x 65 so that a splat on the optical axis is centred on pixel (32, 32).
const Camera kCamera = forward_camera(65, 65, 100.0);
constexpr int kCentre = 32 * 65 + 32;

RenderOutput render_splats(const std::vector<Splat>& splats, const Camera& camera = kCamera,
                           std::array<float, 3> background = {0.f, 0.f, 0.f}) {
    GaussianCloud cloud;
    for (const Splat& s : splats) add_splat(cloud, s);
    return render(cloud, camera, {.background = background});
}

glm::dvec3 rgb_at(const RenderOutput& out, size_t pixel) {
    return {out.rgb[pixel * 3], out.rgb[pixel * 3 + 1], out.rgb[pixel * 3 + 2]};
}

void expect_rgb_near(const glm::dvec3& actual, const glm::dvec3& expected, double tolerance) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(actual[c], expected[c], tolerance) << "channel " << c;
}

TEST(Render, EmptySceneIsTheBackground) {
    const RenderOutput out = render_splats({}, kCamera, {0.25f, 0.5f, 1.0f});
    ASSERT_EQ(out.width, 65);
    ASSERT_EQ(out.height, 65);
    ASSERT_EQ(out.rgb.size(), 65u * 65 * 3);
    for (size_t i = 0; i < out.alpha.size(); ++i) {
        ASSERT_EQ(rgb_at(out, i), glm::dvec3(0.25, 0.5, 1.0));
        ASSERT_EQ(out.alpha[i], 0.0f);
        ASSERT_EQ(out.depth[i], 0.0f);
        ASSERT_EQ(out.contributors[i], 0u);
    }
}

TEST(Render, CentrePixelGetsTheOpacityAndTheBackgroundThroughT) {
    const glm::dvec3 background{0.2, 0.4, 0.6}, color{1.0, 0.5, 0.25};
    for (double opacity : {0.5, 0.3, 0.999}) {
        const RenderOutput out = render_splats({{.position = {0.0, 0.0, 5.0}, .opacity = opacity, .color = color}},
                                               kCamera, {0.2f, 0.4f, 0.6f});
        const double alpha = std::min(static_cast<double>(kMaxAlpha), opacity);
        EXPECT_NEAR(out.alpha[kCentre], alpha, 1e-6) << opacity;
        expect_rgb_near(rgb_at(out, kCentre), color * alpha + background * (1.0 - alpha), 1e-6);
        EXPECT_NEAR(out.depth[kCentre], 5.0, 1e-6);
        EXPECT_EQ(out.contributors[kCentre], 1u);
        // A corner pixel, far outside the splat, is background only.
        expect_rgb_near(rgb_at(out, 0), background, 1e-7);
        EXPECT_EQ(out.alpha[0], 0.0f);
    }
    // One pixel to the right: alpha = o exp(-0.5 d^2 / a) with a = 4 + 0.3 (see project_test).
    const RenderOutput out = render_splats({{.position = {0.0, 0.0, 5.0}, .opacity = 0.5}});
    EXPECT_NEAR(out.alpha[kCentre + 1], 0.5 * std::exp(-0.5 / (4.0 + kLowPassFilter)), 1e-6);
}

TEST(Render, GaussiansAtOrBehindTheNearPlaneContributeNothing) {
    for (double z : {-5.0, 0.0, 0.19}) {
        const RenderOutput out = render_splats({{.position = {0.0, 0.0, z}, .scale = glm::dvec3(1.0), .opacity = 0.9}});
        EXPECT_TRUE(std::all_of(out.alpha.begin(), out.alpha.end(), [](float a) { return a == 0.0f; })) << z;
        EXPECT_TRUE(std::all_of(out.contributors.begin(), out.contributors.end(), [](uint32_t c) { return c == 0; }));
    }
    const RenderOutput kept = render_splats({{.position = {0.0, 0.0, 0.21}, .opacity = 0.9}});
    EXPECT_NEAR(kept.alpha[kCentre], 0.9, 1e-6);
}

TEST(Render, NearerOpaqueGaussianWinsWhateverTheInputOrder) {
    const Splat red{.position = {0.0, 0.0, 3.0}, .scale = glm::dvec3(0.2), .opacity = 0.999, .color = {1.0, 0.0, 0.0}};
    const Splat blue{.position = {0.0, 0.0, 6.0}, .scale = glm::dvec3(0.4), .opacity = 0.999, .color = {0.0, 0.0, 1.0}};
    const RenderOutput a = render_splats({red, blue}), b = render_splats({blue, red});
    EXPECT_EQ(a.rgb, b.rgb);
    EXPECT_EQ(a.depth, b.depth);
    EXPECT_EQ(a.contributors, b.contributors);
    // Red takes 0.99; blue would take 0.99 of the remaining 0.01, but T would drop below 1e-4.
    expect_rgb_near(rgb_at(a, kCentre), {kMaxAlpha, 0.0, 0.0}, 1e-6);
    EXPECT_EQ(a.contributors[kCentre], 1u);
}

TEST(Render, DepthIsTheWeightedMeanOfTheBlendedDepths) {
    const Splat front{.position = {0.0, 0.0, 4.0}, .opacity = 0.6};
    const Splat back{.position = {0.0, 0.0, 8.0}, .opacity = 0.5};
    const RenderOutput out = render_splats({back, front});
    const double w_front = 0.6, w_back = 0.5 * (1.0 - 0.6);
    EXPECT_NEAR(out.depth[kCentre], (4.0 * w_front + 8.0 * w_back) / (w_front + w_back), 1e-5);
    EXPECT_NEAR(out.alpha[kCentre], w_front + w_back, 1e-6);
    EXPECT_EQ(out.contributors[kCentre], 2u);
}

TEST(Render, StopsBeforeTransmittanceFallsBelowTheFloor) {
    // Eight splats of opacity 0.8, one behind the other: T = 0.2^k, and 0.2^6 = 6.4e-5 < 1e-4,
    // so five are blended and the sixth ends the walk.
    std::vector<Splat> stack;
    for (int k = 0; k < 8; ++k) stack.push_back({.position = {0.0, 0.0, 5.0 + 0.1 * k}, .opacity = 0.8});
    RenderOutput out = render_splats(stack);
    EXPECT_EQ(out.contributors[kCentre], 5u);
    EXPECT_NEAR(out.alpha[kCentre], 1.0 - std::pow(0.2, 5), 1e-6);

    // A splat too faint to count (alpha < 1/255) in front is not blended, so not counted.
    stack.push_back({.position = {0.0, 0.0, 1.0}, .opacity = 0.003});
    out = render_splats(stack);
    EXPECT_EQ(out.contributors[kCentre], 5u);
    EXPECT_NEAR(out.alpha[kCentre], 1.0 - std::pow(0.2, 5), 1e-6);

    // At the alpha cap, (1 - 0.99f)^2 = 9.99998e-5 is already below 0.0001f: one splat only, as in
    // the float reference.
    std::vector<Splat> opaque(6, Splat{.position = {0.0, 0.0, 5.0}, .opacity = 0.9999});
    out = render_splats(opaque);
    EXPECT_EQ(out.contributors[kCentre], 1u);
    EXPECT_NEAR(out.alpha[kCentre], kMaxAlpha, 1e-7);
}

TEST(Render, EqualDepthsBlendInInputOrder) {
    const Splat red{.position = {0.0, 0.0, 5.0}, .opacity = 0.5, .color = {1.0, 0.0, 0.0}};
    const Splat green{.position = {0.0, 0.0, 5.0}, .opacity = 0.5, .color = {0.0, 1.0, 0.0}};
    const glm::dvec3 first = rgb_at(render_splats({red, green}), kCentre);
    EXPECT_NEAR(first.x, 0.5, 1e-6);
    EXPECT_NEAR(first.y, 0.25, 1e-6);
    const glm::dvec3 swapped = rgb_at(render_splats({green, red}), kCentre);
    EXPECT_NEAR(swapped.x, 0.25, 1e-6);
    EXPECT_NEAR(swapped.y, 0.5, 1e-6);
}

TEST(Render, OffCentrePrincipalPointShiftsTheImage) {
    const std::vector<Splat> splats{{.position = {0.1, -0.05, 5.0}, .opacity = 0.7},
                                    {.position = {-0.2, 0.1, 6.0}, .scale = {0.3, 0.1, 0.2}, .opacity = 0.6}};
    Camera shifted = kCamera;
    shifted.cx += 9.0;
    shifted.cy -= 4.0;
    const RenderOutput a = render_splats(splats), b = render_splats(splats, shifted);
    for (int y = 4; y < 65; ++y)
        for (int x = 0; x + 9 < 65; ++x) {
            const size_t from = static_cast<size_t>(y) * 65 + x, to = static_cast<size_t>(y - 4) * 65 + x + 9;
            ASSERT_NEAR(a.alpha[from], b.alpha[to], 1e-6) << x << ", " << y;
            ASSERT_NEAR(a.rgb[from * 3], b.rgb[to * 3], 1e-6) << x << ", " << y;
        }
}

TEST(Render, AnyImageSizeRendersEveryPixel) {
    const Camera camera = forward_camera(333, 777, 400.0);
    // Splats centred on the last pixel of the partial tile column and row, and on the first pixel.
    const RenderOutput out = render_splats({{.position = at_pixel(camera, 332.0, 776.0, 5.0), .opacity = 0.5},
                                            {.position = at_pixel(camera, 0.0, 0.0, 5.0), .opacity = 0.4}},
                                           camera, {0.f, 0.f, 1.f});
    ASSERT_EQ(out.width, 333);
    ASSERT_EQ(out.height, 777);
    ASSERT_EQ(out.alpha.size(), 333u * 777);
    EXPECT_NEAR(out.alpha[776 * 333 + 332], 0.5, 1e-6);
    EXPECT_NEAR(out.alpha[0], 0.4, 1e-6);
    EXPECT_EQ(out.alpha[400 * 333 + 160], 0.0f);
    EXPECT_EQ(out.rgb[(400 * 333 + 160) * 3 + 2], 1.0f);
}

TEST(Render, MaxShDegreeIgnoresHigherBands) {
    GaussianCloud cloud;
    cloud.sh_degree = 3;
    add_splat(cloud, {.position = {0.05, 0.0, 5.0}, .opacity = 0.8});
    for (size_t k = 3; k < cloud.sh.size(); ++k) cloud.sh[k] = 0.3f * std::sin(static_cast<float>(k));
    const RenderOutput full = render(cloud, kCamera, {.max_sh_degree = 3});
    const RenderOutput capped = render(cloud, kCamera, {.max_sh_degree = 0});
    const RenderOutput truncated = render(cloud.with_sh_degree(0), kCamera, {});
    EXPECT_EQ(capped.rgb, truncated.rgb);
    EXPECT_NE(full.rgb, capped.rgb);
}

TEST(Render, RejectsAnInvalidCameraOrCloud) {
    Camera bad = kCamera;
    bad.fx = 0.0;
    EXPECT_THROW(render_splats({}, bad), InputError);
    GaussianCloud cloud;
    add_splat(cloud, {});
    cloud.sh.pop_back();
    EXPECT_THROW(render(cloud, kCamera, {}), std::runtime_error);
}

// Binning by tiles must not change the result: every pixel equals blending, in (float depth,
// index) order, all the visible splats whose tile rectangle covers that pixel's tile.
TEST(Render, TileListsMatchAPerPixelSelection) {
    const Camera camera = forward_camera(70, 45, 60.0);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    GaussianCloud cloud;
    for (int i = 0; i < 60; ++i) {
        const double z = i % 10 == 0 ? 4.0 : 2.0 + 6.0 * unit(rng);  // some exact depth ties
        add_splat(cloud, {.position = at_pixel(camera, -10.0 + 90.0 * unit(rng), -10.0 + 65.0 * unit(rng), z),
                          .scale = {0.02 + 0.2 * unit(rng), 0.02 + 0.2 * unit(rng), 0.02 + 0.2 * unit(rng)},
                          .rotation = {unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5},
                          .opacity = 0.05 + 0.9 * unit(rng),
                          .color = {unit(rng), unit(rng), unit(rng)}});
    }
    const RenderOutput out = render(cloud, camera, {});
    std::vector<ProjectedGaussian> splats;
    for (size_t i = 0; i < cloud.size(); ++i) splats.push_back(project(cloud, i, camera, 0));
    for (int y = 0; y < camera.height; ++y)
        for (int x = 0; x < camera.width; ++x) {
            const glm::ivec2 tile(x / static_cast<int>(kTileWidth), y / static_cast<int>(kTileHeight));
            std::vector<size_t> order;
            for (size_t i = 0; i < splats.size(); ++i)
                if (splats[i].visible && glm::all(glm::greaterThanEqual(tile, splats[i].rect_min)) &&
                    glm::all(glm::lessThan(tile, splats[i].rect_max)))
                    order.push_back(i);
            std::sort(order.begin(), order.end(), [&splats](size_t l, size_t r) {
                const float dl = static_cast<float>(splats[l].depth), dr = static_cast<float>(splats[r].depth);
                return dl != dr ? dl < dr : l < r;
            });
            double t = 1.0, red = 0.0;
            for (size_t i : order) {
                const glm::dvec2 d = splats[i].mean - glm::dvec2(x, y);
                const glm::dvec3 c = splats[i].conic;
                const double power = -0.5 * (c.x * d.x * d.x + c.z * d.y * d.y) - c.y * d.x * d.y;
                const double alpha = std::min(static_cast<double>(kMaxAlpha), splats[i].opacity * std::exp(power));
                if (power > 0.0 || alpha < kMinAlpha) continue;
                if (t * (1.0 - alpha) < kMinTransmittance) break;
                red += splats[i].color[0] * alpha * t;
                t *= 1.0 - alpha;
            }
            const size_t p = static_cast<size_t>(y) * camera.width + x;
            ASSERT_NEAR(out.rgb[p * 3], red, 1e-6) << x << ", " << y;
            ASSERT_NEAR(out.alpha[p], 1.0 - t, 1e-6) << x << ", " << y;
        }
}

}  // namespace
}  // namespace vksplat::reference
