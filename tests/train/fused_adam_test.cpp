// A training step hands each gradient straight to Adam inside the preprocess backward
// (shaders/train/adam.glsl) and keeps no gradient array. Checked against Adam taken on the host
// from the gradients the same backward writes out when asked for them: every parameter group's
// rate, the bias corrections, moments carried in from earlier steps, 3DGS-MCMC's regularisers
// (which reach Gaussians no view drew), Gaussians the frame did not draw at all, and SH bands
// above the frame's degree (zero gradient, yet their moments decay and they move).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "train/differentiable_renderer.hpp"  // first: its volk must come before the public headers' Vulkan
#include "gpu/transfer.hpp"
#include "render/frame_layout.hpp"
#include "shaders/train/adam_step.h"
#include "support/gpu_fixture.hpp"
#include "support/scenes.hpp"
#include "train/trainable_scene.hpp"
#include "vksplat/train/gradients.hpp"

namespace vksplat::test {
namespace {

class FusedAdam : public GpuTest {};

// One backward pass of `scene` to the pixel weights `weights` (rgb per pixel) with Adam's step
// (`adam`, its moments set here to the scene's) fused in; returns the step's status.
uint32_t fused_step(const gpu::Context& context, const train::TrainableScene& scene, const Camera& camera,
                    const RenderSettings& settings, const std::vector<float>& weights,
                    shader::train::AdamSettings adam, train::GradientSums sums) {
    adam.first_moment = scene.first_moment.address();
    adam.second_moment = scene.second_moment.address();
    const gpu::Buffer adam_buffer = gpu::upload_buffer(context, &adam, sizeof(adam), "Adam settings");
    const auto [pixels, tiles] = render::image_extent(camera);
    std::vector<float> pixel_weights(size_t(pixels) * 4, 0.0f);
    for (size_t p = 0; p < pixels; ++p) std::copy_n(&weights[3 * p], 3, &pixel_weights[4 * p]);
    const gpu::Buffer pixel_grad = gpu::upload_buffer(context, pixel_weights, "pixel weights");
    train::DifferentiableRenderer renderer(context, sums);
    renderer.ensure(scene.layout.count, pixels, tiles);
    renderer.backpropagate(scene, camera, settings, pixel_grad.address(), adam_buffer.address());
    return renderer.status();
}

// Adam at its first step's bias corrections, every rate 1e-3, no regularisers.
shader::train::AdamSettings first_step_adam() {
    return {.first_moment = {}, .second_moment = {},
            .lr_position = 1e-3f, .lr_scale = 1e-3f, .lr_rotation = 1e-3f,
            .lr_opacity = 1e-3f, .lr_sh_dc = 1e-3f, .lr_sh_rest = 1e-3f,
            .beta1 = 0.9f, .beta2 = 0.999f, .epsilon = 1e-15f,
            .bias_correction1 = 0.1f, .bias_correction2 = 0.001f,
            .opacity_regularization = 0.0f, .scale_regularization = 0.0f};
}

// Zero moments for `cloud`'s layout.
GaussianCloud zero_moments(const GaussianCloud& cloud) {
    const std::vector<float> zeros(train::pack_parameters(cloud).size(), 0.0f);
    return train::unpack_parameters(zeros, uint32_t(cloud.size()), cloud.sh_degree);
}

std::vector<float> random_values(size_t n, uint32_t seed, float lo, float hi) {
    std::mt19937 rng(seed);
    std::vector<float> values(n);
    for (auto& v : values) v = std::uniform_real_distribution<float>(lo, hi)(rng);
    return values;
}

// The SH block starts at 11 N floats: 300 Gaussians put it on a 16-byte boundary, 301 do not, so
// that the SH backward steps the block's first and last chunks of four floats one at a time.
TEST_F(FusedAdam, StepsAsAdamOnTheWrittenGradients) {
    // Fixed-point sums give both backward passes the same gradients to the bit.
    if (!context().info().int64_atomics) GTEST_SKIP() << "no 64-bit buffer atomics on this device";
    for (const uint32_t count : {300u, 301u}) {
        SCOPED_TRACE(std::to_string(count) + " Gaussians");
        GaussianCloud cloud = random_scene(11, count, 3, 3.0f, 7.0f, 0.05f, 0.3f, 0.8f);
        for (size_t i = 0; i < cloud.size(); i += 10) cloud.positions[3 * i + 2] = -4.0f;  // behind the camera
        const Camera camera = forward_camera(64, 48, 60.0);
        RenderSettings settings;
        settings.max_sh_degree = 1;  // bands 2 and 3 get no gradient
        const uint32_t pixels = render::image_extent(camera).pixels;
        const std::vector<float> weights = random_values(size_t(pixels) * 3, 3, -1.0f, 1.0f);

        // Moments as several steps would have left them.
        const size_t floats = train::pack_parameters(cloud).size();
        const std::vector<float> first = random_values(floats, 4, -0.01f, 0.01f);
        const std::vector<float> second = random_values(floats, 5, 1e-8f, 1e-4f);
        const auto as_cloud = [&](const std::vector<float>& packed) {
            return train::unpack_parameters(packed, uint32_t(cloud.size()), cloud.sh_degree);
        };
        const GaussianCloud first_cloud = as_cloud(first), second_cloud = as_cloud(second);

        // The moments' addresses are fused_step's to set.
        const shader::train::AdamSettings adam{.first_moment = {},
                                         .second_moment = {},
                                         .lr_position = 1.6e-4f,
                                         .lr_scale = 5e-3f,
                                         .lr_rotation = 1e-3f,
                                         .lr_opacity = 0.05f,
                                         .lr_sh_dc = 2.5e-3f,
                                         .lr_sh_rest = 1.25e-4f,
                                         .beta1 = 0.9f,
                                         .beta2 = 0.999f,
                                         .epsilon = 1e-15f,
                                         .bias_correction1 = 1.0f - std::pow(0.9f, 3.0f),
                                         .bias_correction2 = 1.0f - std::pow(0.999f, 3.0f),
                                         .opacity_regularization = 0.01f / 300.0f,
                                         .scale_regularization = 0.01f / 900.0f};

        // The fused step on the device.
        const train::TrainableScene scene =
            train::TrainableScene::upload(context(), cloud, &first_cloud, &second_cloud);
        ASSERT_EQ(fused_step(context(), scene, camera, settings, weights, adam, train::GradientSums::fixed_point) &
                      train::kStepNonfinite,
                  0u);
        const auto params = train::pack_parameters(scene.download(context()));
        const auto m1 = train::pack_parameters(scene.download(context(), scene.first_moment));
        const auto m2 = train::pack_parameters(scene.download(context(), scene.second_moment));

        // Adam on the host, from the written gradients.
        const auto gradient =
            train::pack_parameters(train::render_gradients(context(), cloud, camera, settings, weights,
                                                           train::GradientSums::fixed_point)
                                       .gradient);
        const auto raw = train::pack_parameters(cloud);
        const train::ParameterLayout layout{uint32_t(cloud.size()), uint32_t(cloud.sh_coefficients())};
        const uint32_t sh_floats = layout.sh_coefficients * 3;
        size_t moved_undrawn = 0;
        for (size_t i = 0; i < floats; ++i) {
            float g = gradient[i], rate = 0;
            if (i < layout.log_scales()) {
                rate = adam.lr_position;
            } else if (i < layout.rotations()) {
                rate = adam.lr_scale;
                g += adam.scale_regularization * std::exp(raw[i]);
            } else if (i < layout.opacities()) {
                rate = adam.lr_rotation;
            } else if (i < layout.sh()) {
                rate = adam.lr_opacity;
                const float opacity = 1.0f / (1.0f + std::exp(-raw[i]));
                g += adam.opacity_regularization * opacity * (1.0f - opacity);
            } else {
                rate = (i - layout.sh()) % sh_floats < 3 ? adam.lr_sh_dc : adam.lr_sh_rest;
            }
            const float m = adam.beta1 * first[i] + (1 - adam.beta1) * g;
            const float v = adam.beta2 * second[i] + (1 - adam.beta2) * g * g;
            const float expected = raw[i] - rate * ((m / adam.bias_correction1) /
                                                    (std::sqrt(v / adam.bias_correction2) + adam.epsilon));
            SCOPED_TRACE(i);
            EXPECT_NEAR(m1[i], m, 1e-6f * std::abs(m) + 1e-12f);
            EXPECT_NEAR(m2[i], v, 1e-6f * v + 1e-15f);
            EXPECT_NEAR(params[i], expected, 1e-6f * std::max(1.0f, std::abs(expected)));
            if (i < layout.log_scales() && (i / 3) % 10 == 0 && params[i] != raw[i]) ++moved_undrawn;
        }
        // The Gaussians behind the camera moved by their moments alone.
        EXPECT_EQ(moved_undrawn, 3 * ((cloud.size() + 9) / 10));
    }
}

// A NaN in one pixel's gradient reaches the Gaussians drawn there: those whose gradient is not
// finite (as the written gradients show) keep their parameters and moments, every other Gaussian
// steps, and the step's status says a gradient was not finite.
TEST_F(FusedAdam, AGaussianWithANonFiniteGradientAloneDoesNotStep) {
    // Float sums: fixed-point ones cannot say which Gaussians a NaN reached (the next test).
    const GaussianCloud cloud = random_scene(12, 200, 1, 3.0f, 7.0f, 0.02f, 0.1f, 0.8f);
    const Camera camera = forward_camera(64, 48, 60.0);
    const uint32_t pixels = render::image_extent(camera).pixels;
    std::vector<float> weights(size_t(pixels) * 3, 0.1f);
    weights[(24 * 64 + 32) * 3] = std::nanf("");
    const auto gradient = train::pack_parameters(
        train::render_gradients(context(), cloud, camera, {}, weights, train::GradientSums::device_default).gradient);

    const GaussianCloud zeros = zero_moments(cloud);
    const train::TrainableScene scene = train::TrainableScene::upload(context(), cloud, &zeros, &zeros);
    EXPECT_NE(fused_step(context(), scene, camera, {}, weights, first_step_adam(),
                         train::GradientSums::device_default) &
                  train::kStepNonfinite,
              0u);
    const auto params = train::pack_parameters(scene.download(context()));
    const auto m1 = train::pack_parameters(scene.download(context(), scene.first_moment));
    const auto raw = train::pack_parameters(cloud);

    const train::ParameterLayout layout{uint32_t(cloud.size()), uint32_t(cloud.sh_coefficients())};
    const uint32_t sh_floats = layout.sh_coefficients * 3;
    size_t kept = 0, stepped = 0;
    for (uint32_t i = 0; i < layout.count; ++i) {
        std::vector<uint64_t> at;
        for (uint32_t k = 0; k < 3; ++k) at.insert(at.end(), {layout.positions() + 3 * i + k, layout.log_scales() + 3 * i + k});
        for (uint32_t k = 0; k < 4; ++k) at.push_back(layout.rotations() + 4 * i + k);
        at.push_back(layout.opacities() + i);
        for (uint32_t k = 0; k < sh_floats; ++k) at.push_back(layout.sh() + sh_floats * i + k);
        bool finite = true, same = true;
        for (uint64_t a : at) {
            finite = finite && std::isfinite(gradient[a]);
            same = same && params[a] == raw[a] && m1[a] == 0.0f;
        }
        SCOPED_TRACE(i);
        if (finite) {
            EXPECT_FALSE(same) << "a Gaussian with finite gradients did not step";
            ++stepped;
        } else {
            EXPECT_TRUE(same) << "a Gaussian with a non-finite gradient stepped";
            ++kept;
        }
    }
    EXPECT_GT(kept, 0u);
    EXPECT_GT(stepped, kept);
}

// Fixed-point sums cannot carry a NaN (nor an infinity) to the totals of the Gaussians it reached,
// so which ones it reached is lost: the step's status says so, and no Gaussian steps. Without the
// NaN the same step moves them.
TEST_F(FusedAdam, WithFixedPointSumsANonFiniteGradientStopsTheWholeStep) {
    if (!context().info().int64_atomics) GTEST_SKIP() << "no 64-bit buffer atomics on this device";
    const GaussianCloud cloud = random_scene(12, 200, 1, 3.0f, 7.0f, 0.02f, 0.1f, 0.8f);
    const Camera camera = forward_camera(64, 48, 60.0);
    const uint32_t pixels = render::image_extent(camera).pixels;
    const auto raw = train::pack_parameters(cloud);
    const GaussianCloud zeros = zero_moments(cloud);
    for (const bool nan : {true, false}) {
        SCOPED_TRACE(nan ? "a NaN in one pixel" : "no NaN");
        std::vector<float> weights(size_t(pixels) * 3, 0.1f);
        if (nan) weights[(24 * 64 + 32) * 3] = std::nanf("");
        const train::TrainableScene scene = train::TrainableScene::upload(context(), cloud, &zeros, &zeros);
        const uint32_t status =
            fused_step(context(), scene, camera, {}, weights, first_step_adam(), train::GradientSums::fixed_point);
        EXPECT_EQ(status & train::kStepNonfinite, nan ? train::kStepNonfinite : 0u);
        EXPECT_EQ(status & train::kStepNonfiniteSums, nan ? train::kStepNonfiniteSums : 0u);
        const auto params = train::pack_parameters(scene.download(context()));
        const auto m1 = train::pack_parameters(scene.download(context(), scene.first_moment));
        size_t moved = 0;
        for (size_t i = 0; i < raw.size(); ++i) moved += params[i] != raw[i] || m1[i] != 0.0f;
        if (nan) EXPECT_EQ(moved, 0u);
        else EXPECT_GT(moved, raw.size() / 2);
    }
}

}  // namespace
}  // namespace vksplat::test
