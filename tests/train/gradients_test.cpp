// The backward passes against central finite differences of the double-precision reference
// rasterizer: for L = sum of w . rgb over the picture (random weights w), the GPU's gradient of
// every raw parameter type (position, log-scale, quaternion, opacity logit, SH of each degree)
// must agree with (L(p + h) - L(p - h)) / 2h to a relative error of 1e-3 per type; the blend
// backward's per-splat form as its per-pixel one. The other sums and forms agree with the default.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "train/differentiable_renderer.hpp"  // first: its volk must come before the public headers' Vulkan
#include "support/gpu_fixture.hpp"
#include "support/scenes.hpp"
#include "vksplat/reference/rasterizer.hpp"
#include "vksplat/train/gradients.hpp"

namespace vksplat::test {
namespace {

constexpr double kMaxRelativeError = 1e-3;

// A few overlapping Gaussians well inside the view, with opacities below the 0.99 clamp and SH
// colours far from the clamp at 0: the picture is smooth in every parameter except where a
// pixel's alpha crosses 1/255, which the finite differences below detect and step around.
GaussianCloud smooth_scene(uint32_t seed, size_t n, int sh_degree) {
    std::mt19937 rng(seed);
    auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
    GaussianCloud cloud;
    cloud.sh_degree = sh_degree;
    for (size_t i = 0; i < n; ++i) {
        Splat splat;
        splat.position = {uniform(-0.8, 0.8), uniform(-0.6, 0.6), uniform(3.0, 5.0)};
        splat.scale = {uniform(0.08, 0.35), uniform(0.08, 0.35), uniform(0.08, 0.35)};
        splat.rotation = {uniform(0.3, 1.0), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
        splat.opacity = uniform(0.25, 0.75);
        splat.color = {uniform(0.3, 0.9), uniform(0.3, 0.9), uniform(0.3, 0.9)};
        add_splat(cloud, splat);
        // Raw quaternions are not unit length in trained scenes either.
        for (int k = 0; k < 4; ++k) cloud.rotations[4 * i + k] *= float(uniform(0.7, 1.6));
        const int coefficients = cloud.sh_coefficients();
        for (int c = 3; c < coefficients * 3; ++c) cloud.sh[i * coefficients * 3 + c] = float(uniform(-0.08, 0.08));
    }
    return cloud;
}

double weighted_sum(const std::vector<double>& rgb, const std::vector<float>& weights) {
    double sum = 0;
    for (size_t i = 0; i < rgb.size(); ++i) sum += rgb[i] * weights[i];
    return sum;
}

struct FiniteDifference {
    double value = 0;
    bool smooth = true;  // false: a jump (alpha crossing 1/255) sits within every step tried
};

// Central difference in one float parameter, with the step actually taken (the perturbed values
// are floats). Differences at h and h/2 agree to O(h^2) where the picture is smooth; a jump
// within the step (a pixel's alpha crossing 1/255, a tile rectangle growing) makes them differ,
// and the step is halved until it lies inside the jump's distance, or the parameter is reported
// as not smooth there.
FiniteDifference finite_difference(GaussianCloud& cloud, float& parameter, const Camera& camera,
                                   const RenderSettings& settings, const std::vector<float>& weights) {
    const float original = parameter;
    const auto central = [&](double h) {
        const float up = float(original + h), down = float(original - h);
        parameter = up;
        const double l_up = weighted_sum(reference::render_rgb(cloud, camera, settings), weights);
        parameter = down;
        const double l_down = weighted_sum(reference::render_rgb(cloud, camera, settings), weights);
        parameter = original;
        return (l_up - l_down) / (double(up) - double(down));
    };
    double h = 1e-3 * std::max(1.0, std::abs(double(original)));
    double wide = central(h);
    for (; h > 1e-6; h *= 0.5) {
        const double narrow = central(h * 0.5);
        if (std::abs(wide - narrow) <= 1e-4 * std::abs(narrow) + 1e-6) return {narrow, true};
        wide = narrow;
    }
    return {0, false};
}

struct TypeError {
    double relative = 0;   // |g_gpu - g_fd| / |g_fd| over the type's smooth entries
    size_t compared = 0, not_smooth = 0;
};

TypeError compare(GaussianCloud& cloud, std::vector<float>& parameters, const std::vector<float>& gpu,
                  size_t first, size_t stride, size_t count_per, const Camera& camera, const RenderSettings& settings,
                  const std::vector<float>& weights) {
    double diff2 = 0, norm2 = 0;
    TypeError error;
    for (size_t i = 0; i < cloud.size(); ++i)
        for (size_t k = first; k < first + count_per; ++k) {
            const size_t at = i * stride + k;
            const FiniteDifference fd = finite_difference(cloud, parameters[at], camera, settings, weights);
            if (!fd.smooth) {
                ++error.not_smooth;
                continue;
            }
            ++error.compared;
            diff2 += (gpu[at] - fd.value) * (gpu[at] - fd.value);
            norm2 += fd.value * fd.value;
        }
    error.relative = norm2 > 0 ? std::sqrt(diff2 / norm2) : std::sqrt(diff2);
    return error;
}

// Edge cases of the forward pass that the backward must follow: a Gaussian beyond the Jacobian's
// lateral clamp (1.3 tan(fov/2)) but large enough to reach into the picture, and one whose red
// channel is clamped at 0 (it passes no gradient there).
GaussianCloud edge_scene(uint32_t seed, int sh_degree) {
    GaussianCloud cloud = smooth_scene(seed, 8, sh_degree);
    const int stride = cloud.sh_coefficients() * 3;
    cloud.positions[0] = 0.8f * cloud.positions[2];  // x / z = 0.8 > 1.3 * 32 / 60
    for (int k = 0; k < 3; ++k) cloud.log_scales[k] = std::log(0.6f);
    cloud.sh[1 * stride + 0] = -3.0f;                 // red: 0.5 + C0 * (-3) < 0
    return cloud;
}

class Gradients : public GpuTest {
protected:
    void check_every_type(uint32_t seed, int sh_degree, const std::array<float, 3>& background,
                          bool edges = false, train::BlendBackward form = train::BlendBackward::per_pixel) {
        GaussianCloud cloud = edges ? edge_scene(seed, sh_degree) : smooth_scene(seed, 10, sh_degree);
        const Camera camera = forward_camera(64, 48, 60.0);
        RenderSettings settings;
        settings.background = background;
        std::mt19937 rng(seed + 1);
        std::vector<float> weights(size_t(camera.width) * camera.height * 3);
        for (auto& w : weights) w = std::uniform_real_distribution<float>(-1.0f, 1.0f)(rng);

        const train::RenderGradients gpu =
            train::render_gradients(context(), cloud, camera, settings, weights, train::GradientSums::device_default, form);
        // The picture differentiated is the renderer's picture.
        const auto expected = reference::render_rgb(cloud, camera, settings);
        for (size_t i = 0; i < expected.size(); ++i) ASSERT_NEAR(gpu.image.rgb[i], expected[i], 2e-5) << i;

        const int coefficients = cloud.sh_coefficients();
        struct Case {
            std::string name;
            std::vector<float>* parameters;
            const std::vector<float>* gradient;
            size_t stride, first, count;
        };
        std::vector<Case> cases = {
            {"position", &cloud.positions, &gpu.gradient.positions, 3, 0, 3},
            {"log-scale", &cloud.log_scales, &gpu.gradient.log_scales, 3, 0, 3},
            {"rotation", &cloud.rotations, &gpu.gradient.rotations, 4, 0, 4},
            {"opacity logit", &cloud.opacity_logits, &gpu.gradient.opacity_logits, 1, 0, 1},
        };
        for (int degree = 0; degree <= sh_degree; ++degree) {
            // The coefficients of this band: from the previous degree's count up to this one's.
            const size_t first = size_t(sh_coefficients_for_degree(degree - 1)) * 3;
            const size_t end = size_t(sh_coefficients_for_degree(degree)) * 3;
            cases.push_back({"SH degree " + std::to_string(degree), &cloud.sh, &gpu.gradient.sh,
                             size_t(coefficients) * 3, first, end - first});
        }
        for (const auto& c : cases) {
            const TypeError error =
                compare(cloud, *c.parameters, *c.gradient, c.first, c.stride, c.count, camera, settings, weights);
            std::printf("  %-14s relative error %.2e over %zu entries (%zu at a jump, skipped)\n", c.name.c_str(),
                        error.relative, error.compared, error.not_smooth);
            EXPECT_LE(error.relative, kMaxRelativeError) << c.name;
            EXPECT_GT(error.compared, 0u) << c.name;
            EXPECT_LE(error.not_smooth * 20, error.compared + error.not_smooth) << c.name << ": too many jumps";
        }
    }
};

TEST_F(Gradients, EveryParameterTypeMatchesFiniteDifferences) { check_every_type(7, 3, {0.0f, 0.0f, 0.0f}); }

TEST_F(Gradients, WithABackgroundAndLowerShDegree) { check_every_type(21, 1, {0.3f, 0.6f, 1.0f}); }

TEST_F(Gradients, ThroughTheJacobianClampAndTheColourClamp) { check_every_type(33, 2, {0.0f, 0.0f, 0.0f}, true); }

TEST_F(Gradients, PerSplatMatchesFiniteDifferences) {
    check_every_type(7, 3, {0.0f, 0.0f, 0.0f}, false, train::BlendBackward::per_splat);
}

TEST_F(Gradients, PerSplatWithABackgroundThroughTheClamps) {
    check_every_type(21, 1, {0.3f, 0.6f, 1.0f}, true, train::BlendBackward::per_splat);
}

std::vector<float> random_weights(const Camera& camera, uint32_t seed) {
    std::mt19937 rng(seed);
    std::vector<float> weights(size_t(camera.width) * camera.height * 3);
    for (auto& w : weights) w = std::uniform_real_distribution<float>(-1.0f, 1.0f)(rng);
    return weights;
}

// Two backward passes give the same gradients: equal up to the order of float additions (and, for
// fixed point, its 2^-40 steps), `tolerance` relative per parameter type.
void expect_same_gradients(const train::RenderGradients& a, const train::RenderGradients& b,
                           double tolerance = 1e-5) {
    const auto relative = [](const std::vector<float>& x, const std::vector<float>& y) {
        double diff = 0, norm = 0;
        for (size_t i = 0; i < x.size(); ++i) {
            diff += double(x[i] - y[i]) * (x[i] - y[i]);
            norm += double(y[i]) * y[i];
        }
        return std::sqrt(diff / std::max(norm, 1e-30));
    };
    EXPECT_LE(relative(a.gradient.positions, b.gradient.positions), tolerance);
    EXPECT_LE(relative(a.gradient.log_scales, b.gradient.log_scales), tolerance);
    EXPECT_LE(relative(a.gradient.rotations, b.gradient.rotations), tolerance);
    EXPECT_LE(relative(a.gradient.opacity_logits, b.gradient.opacity_logits), tolerance);
    EXPECT_LE(relative(a.gradient.sh, b.gradient.sh), tolerance);
    double norm = 0;
    for (float g : b.gradient.positions) norm += double(g) * g;
    EXPECT_GT(norm, 0.0);  // not two empty gradients agreeing
}

// The compare-and-swap loop (devices without float atomics) and the fixed-point sums (--deterministic)
// give the same gradients as float atomics.
void expect_same_gradients(const gpu::Context& context, train::GradientSums sums) {
    const GaussianCloud cloud = random_scene(17, 300, 3);
    const Camera camera = forward_camera(96, 64, 80.0);
    const std::vector<float> weights = random_weights(camera, 2);
    std::printf("  float atomics on this device: %s\n", context.info().float_atomics ? "yes" : "no");
    expect_same_gradients(train::render_gradients(context, cloud, camera, {}, weights, sums),
                          train::render_gradients(context, cloud, camera, {}, weights));
}

TEST_F(Gradients, CompareAndSwapSumsAgreeWithFloatAtomics) {
    expect_same_gradients(context(), train::GradientSums::compare_and_swap);
}

TEST_F(Gradients, FixedPointSumsAgreeWithFloatAtomicsAndRepeatExactly) {
    if (!context().info().int64_atomics) GTEST_SKIP() << "no 64-bit buffer atomics on this device";
    expect_same_gradients(context(), train::GradientSums::fixed_point);
    const GaussianCloud cloud = random_scene(5, 2000, 1, 2.0f, 8.0f, 0.05f, 0.6f);
    const Camera camera = forward_camera(128, 96, 100.0);
    const std::vector<float> weights(size_t(camera.width) * camera.height * 3, 0.25f);
    const auto first = train::render_gradients(context(), cloud, camera, {}, weights, train::GradientSums::fixed_point);
    for (int run = 0; run < 3; ++run) {
        const auto again = train::render_gradients(context(), cloud, camera, {}, weights, train::GradientSums::fixed_point);
        EXPECT_EQ(again.gradient.positions, first.gradient.positions);
        EXPECT_EQ(again.gradient.sh, first.gradient.sh);
        EXPECT_EQ(again.gradient.opacity_logits, first.gradient.opacity_logits);
    }
}

// The per-splat blend backward gives the per-pixel one's gradients where its bookkeeping could
// slip: splats covering many tiles, tiles of more splats than a batch (256) holds, pixels whose
// loss is masked out (no gradient; their replay still runs), and tiles cut by the picture's edge
// (100x70: neither is a multiple of 16). With float atomics and with compare-and-swap sums.
TEST_F(Gradients, PerSplatAgreesWithPerPixel) {
    struct Case {
        const char* name;
        GaussianCloud cloud;
    };
    const Case cases[] = {
        {"large splats", random_scene(41, 40, 1, 2.0f, 6.0f, 0.4f, 1.5f)},
        {"many overlapping splats", random_scene(42, 3000, 1, 3.0f, 8.0f, 0.05f, 0.4f, 0.8f)},
        {"mixed sizes", random_scene(43, 600, 2, 2.0f, 8.0f, 0.01f, 0.8f)},
    };
    const Camera camera = forward_camera(100, 70, 80.0);
    std::vector<float> weights = random_weights(camera, 5);
    for (int y = 0; y < camera.height; ++y)
        for (int x = 0; x < camera.width; ++x)
            if (x < 30 || (x / 3 + y / 3) % 2 == 0)  // a band and a fine checkerboard masked out
                for (int c = 0; c < 3; ++c) weights[(size_t(y) * camera.width + x) * 3 + c] = 0.0f;
    // The per-pixel reference sums in fixed point, so that it carries no float-order noise of its
    // own; the per-splat sums are float and do. Their order alone moved the log-scale gradients of
    // "mixed sizes" by up to 3.2e-5 relative on lavapipe (they cancel across pixels), so 1e-5 failed
    // about one run in eight: the bound is 1e-4, and a wrong formula moves them by far more.
    constexpr double kFloatOrder = 1e-4;
    for (const auto& c : cases) {
        SCOPED_TRACE(c.name);
        const auto per_pixel = train::render_gradients(context(), c.cloud, camera, {}, weights,
                                                       train::GradientSums::fixed_point,
                                                       train::BlendBackward::per_pixel);
        expect_same_gradients(train::render_gradients(context(), c.cloud, camera, {}, weights,
                                                      train::GradientSums::device_default,
                                                      train::BlendBackward::per_splat),
                              per_pixel, kFloatOrder);
        expect_same_gradients(train::render_gradients(context(), c.cloud, camera, {}, weights,
                                                      train::GradientSums::compare_and_swap,
                                                      train::BlendBackward::per_splat),
                              per_pixel, kFloatOrder);
    }
}

TEST_F(Gradients, PerSplatRefusesFixedPointSums) {
    const GaussianCloud cloud = random_scene(3, 10, 0);
    const Camera camera = forward_camera(32, 32, 40.0);
    EXPECT_THROW(train::render_gradients(context(), cloud, camera, {}, random_weights(camera, 1),
                                         train::GradientSums::fixed_point, train::BlendBackward::per_splat),
                 std::invalid_argument);
}

// The choice of form, given timings: both in turn until each has kTrials, then the lower median
// until the scene doubles or halves; a form asked for is kept; no timings settle on per pixel.
TEST(BlendBackwardChoice, TimesBothInTurnThenKeepsTheLowerMedian) {
    using train::BlendBackward;
    constexpr uint32_t kGaussians = 1000;
    const auto measure = [](double per_pixel_ms, double per_pixel_outlier_ms, double per_splat_ms) {
        train::BlendBackwardChoice choice(BlendBackward::fastest);
        for (size_t i = 0; i < 2 * train::BlendBackwardChoice::kTrials; ++i) {
            choice.scene_size(kGaussians + uint32_t(i));  // densification between the timings
            EXPECT_EQ(choice.chosen(), BlendBackward::fastest);
            const BlendBackward form = choice.next();
            EXPECT_EQ(form, i % 2 == 0 ? BlendBackward::per_pixel : BlendBackward::per_splat);
            choice.timed(form, form == BlendBackward::per_splat ? per_splat_ms
                               : i == 0                         ? per_pixel_outlier_ms
                                                                : per_pixel_ms);
        }
        return choice;
    };
    train::BlendBackwardChoice faster_per_splat = measure(2.0, 2.0, 1.5);
    EXPECT_EQ(faster_per_splat.chosen(), BlendBackward::per_splat);
    for (int i = 0; i < 30; ++i) faster_per_splat.timed(BlendBackward::per_pixel, 0.1);  // decided: no more votes
    EXPECT_EQ(faster_per_splat.chosen(), BlendBackward::per_splat);
    EXPECT_EQ(faster_per_splat.next(), BlendBackward::per_splat);
    // One slow step (the first, say, with its pipelines cold) does not outvote nine.
    EXPECT_EQ(measure(1.0, 100.0, 1.5).chosen(), BlendBackward::per_pixel);
    // A scene grown or shrunk twofold since is timed again; less change keeps the choice.
    for (const uint32_t grown : {2 * kGaussians, kGaussians / 2}) {
        train::BlendBackwardChoice choice = measure(2.0, 2.0, 1.5);
        choice.scene_size(grown);
        EXPECT_EQ(choice.chosen(), BlendBackward::per_splat) << grown;
    }
    for (const uint32_t changed : {2 * kGaussians + 1, kGaussians / 2 - 1}) {
        train::BlendBackwardChoice choice = measure(2.0, 2.0, 1.5);
        choice.scene_size(changed);
        EXPECT_EQ(choice.chosen(), BlendBackward::fastest) << changed;
        EXPECT_EQ(choice.next(), BlendBackward::per_pixel) << changed;
        choice.timed(BlendBackward::per_pixel, 1.0);
        EXPECT_EQ(choice.next(), BlendBackward::per_splat) << changed;
    }

    train::BlendBackwardChoice asked(BlendBackward::per_splat);
    asked.timed(BlendBackward::per_splat, 50.0);
    asked.untimed();
    EXPECT_EQ(asked.next(), BlendBackward::per_splat);
    train::BlendBackwardChoice untimed(BlendBackward::fastest);
    untimed.untimed();
    EXPECT_EQ(untimed.chosen(), BlendBackward::per_pixel);
    EXPECT_EQ(untimed.next(), BlendBackward::per_pixel);
}

}  // namespace
}  // namespace vksplat::test
