// The backward passes against central finite differences of the double-precision reference
// rasterizer: for L = sum of w . rgb over the picture (random weights w), the GPU's gradient of
// every raw parameter type (position, log-scale, quaternion, opacity logit, SH of each degree)
// must agree with (L(p + h) - L(p - h)) / 2h to a relative error of 1e-3 per type.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

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
                          bool edges = false) {
        GaussianCloud cloud = edges ? edge_scene(seed, sh_degree) : smooth_scene(seed, 10, sh_degree);
        const Camera camera = forward_camera(64, 48, 60.0);
        RenderSettings settings;
        settings.background = background;
        std::mt19937 rng(seed + 1);
        std::vector<float> weights(size_t(camera.width) * camera.height * 3);
        for (auto& w : weights) w = std::uniform_real_distribution<float>(-1.0f, 1.0f)(rng);

        const train::RenderGradients gpu = train::render_gradients(context(), cloud, camera, settings, weights);
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

// The compare-and-swap loop (devices without float atomics) and the fixed-point sums (--deterministic)
// give the same gradients as float atomics: equal up to the order of float additions and, for fixed
// point, its 2^-40 steps.
void expect_same_gradients(const gpu::Context& context, train::GradientSums sums) {
    const GaussianCloud cloud = random_scene(17, 300, 3);
    const Camera camera = forward_camera(96, 64, 80.0);
    std::mt19937 rng(2);
    std::vector<float> weights(size_t(camera.width) * camera.height * 3);
    for (auto& w : weights) w = std::uniform_real_distribution<float>(-1.0f, 1.0f)(rng);
    const auto atomics = train::render_gradients(context, cloud, camera, {}, weights);
    const auto cas = train::render_gradients(context, cloud, camera, {}, weights, sums);
    std::printf("  float atomics on this device: %s\n", context.info().float_atomics ? "yes" : "no");
    const auto relative = [](const std::vector<float>& a, const std::vector<float>& b) {
        double diff = 0, norm = 0;
        for (size_t i = 0; i < a.size(); ++i) {
            diff += double(a[i] - b[i]) * (a[i] - b[i]);
            norm += double(b[i]) * b[i];
        }
        return std::sqrt(diff / std::max(norm, 1e-30));
    };
    EXPECT_LE(relative(cas.gradient.positions, atomics.gradient.positions), 1e-5);
    EXPECT_LE(relative(cas.gradient.log_scales, atomics.gradient.log_scales), 1e-5);
    EXPECT_LE(relative(cas.gradient.rotations, atomics.gradient.rotations), 1e-5);
    EXPECT_LE(relative(cas.gradient.opacity_logits, atomics.gradient.opacity_logits), 1e-5);
    EXPECT_LE(relative(cas.gradient.sh, atomics.gradient.sh), 1e-5);
    double norm = 0;
    for (float g : atomics.gradient.positions) norm += double(g) * g;
    EXPECT_GT(norm, 0.0);  // not two empty gradients agreeing
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

}  // namespace
}  // namespace vksplat::test
