// Adaptive density control: which Gaussians the plan clones, splits and prunes, where split
// samples land (plan_densify, on the host), and how the device passes move parameters and Adam's
// moments by a plan and reset opacities (DensifyPasses, on lavapipe).
#include <gtest/gtest.h>

#include <cmath>

// The trainer's internals first: they include volk, which must come before the public headers'
// Vulkan declarations.
#include "train/densify.hpp"
#include "train/host_densify_inputs.hpp"
#include "train/parameter_layout.hpp"

#include "support/gpu_fixture.hpp"
#include "support/scenes.hpp"

namespace vksplat::test {
namespace {

using train::DensifyRules;

// Gaussian i: at (i, 0, 0), isotropic scale scales[i], opacity 0.5, identity rotation, drawn in
// 4 views with mean NDC gradient grads[i] and radius 5 pixels.
HostDensifyInputs inputs_of(const std::vector<float>& scales, const std::vector<float>& grads) {
    const uint32_t n = uint32_t(scales.size());
    const train::ParameterLayout layout{n, 1};
    HostDensifyInputs in(n);
    for (uint32_t i = 0; i < n; ++i) {
        in.geometry[layout.positions() + 3 * i] = float(i);
        for (int k = 0; k < 3; ++k) in.geometry[layout.log_scales() + 3 * i + k] = std::log(scales[i]);
        in.geometry[layout.rotations() + 4 * i] = 1.0f;
        in.sums[i * train::kDensifyStride] = grads[i] * 4.0f;
        in.sums[i * train::kDensifyStride + 1] = 4.0f;
        in.sums[i * train::kDensifyStride + 2] = 5.0f;
    }
    return in;
}

TEST(Densify, ClonesSmallAndSplitsLargeAboveTheThreshold) {
    // Extent 10: percent_dense 0.01 makes 0.1 the boundary between small and large.
    const auto plan = train::plan_densify(inputs_of({0.05f, 0.05f, 0.5f, 0.5f}, {0.001f, 0.0001f, 0.001f, 0.0001f}),
                                          DensifyRules{}, 10.0, 1);
    EXPECT_EQ(plan.report.cloned, 1u);
    EXPECT_EQ(plan.report.split, 1u);
    EXPECT_EQ(plan.report.pruned, 0u);
    EXPECT_EQ(plan.report.after, 6u);
    // Survivors in order (0, 1, 3), then the clone of 0, then 2's two samples.
    EXPECT_EQ(plan.sources, (std::vector<uint32_t>{0, 1, 3, 0, 2, 2}));
    EXPECT_EQ(plan.fresh_from, 3u);
    EXPECT_EQ(plan.override_from, 4u);
    ASSERT_EQ(plan.overrides.size(), 14u);
    for (int s = 0; s < 2; ++s) {
        EXPECT_LT(std::abs(plan.overrides[7 * s] - 2.0f), 4 * 0.5f) << s;
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(std::exp(plan.overrides[7 * s + 3 + k]), 0.5f / 1.6f, 1e-6) << s;
        EXPECT_EQ(plan.overrides[7 * s + 6], 0.0f) << s;  // the parent's opacity logit, as the reference splits
    }
}

TEST(Densify, SplitSamplesFollowTheParentsAnisotropicShape) {
    // One long, rotated Gaussian split many times (one plan per seed): the samples' spread along
    // each world axis must be the parent's standard deviation there.
    const float sx = 2.0f, sy = 0.2f, sz = 0.02f;
    const float half = float(M_SQRT1_2);  // 90 degrees about z: the long axis becomes world y
    HostDensifyInputs in = inputs_of({1.0f}, {1.0f});
    in.geometry[0] = 0.0f;
    const float log_scales[3] = {std::log(sx), std::log(sy), std::log(sz)};
    for (int k = 0; k < 3; ++k) in.geometry[3 + k] = log_scales[k];
    in.geometry[6] = half;
    in.geometry[9] = half;
    double sum[3] = {}, sum_sq[3] = {};
    int samples = 0;
    for (uint64_t seed = 0; seed < 500; ++seed) {
        const auto plan = train::plan_densify(in, DensifyRules{}, 1.0, seed);
        ASSERT_EQ(plan.sources.size(), 2u);
        for (size_t j = 0; j < 2; ++j, ++samples)
            for (int k = 0; k < 3; ++k) {
                const double x = plan.overrides[7 * j + k];
                sum[k] += x;
                sum_sq[k] += x * x;
            }
    }
    const double expected[3] = {sy, sx, sz};
    for (int k = 0; k < 3; ++k) {
        const double mean = sum[k] / samples;
        const double deviation = std::sqrt(sum_sq[k] / samples - mean * mean);
        EXPECT_NEAR(mean, 0.0, 0.15 * expected[k]) << k;
        EXPECT_NEAR(deviation, expected[k], 0.1 * expected[k]) << k;
    }
}

TEST(Densify, PrunesTransparentAlwaysAndLargeOnlyWhenAsked) {
    HostDensifyInputs in = inputs_of({0.05f, 0.05f, 0.05f, 5.0f}, {0, 0, 0, 0});
    in.geometry[10 * 4 + 1] = -6.0f;                   // opacity 0.0025 < 0.005
    in.sums[2 * train::kDensifyStride + 2] = 30.0f;    // 30 px on screen
    DensifyRules rules;
    const auto lenient = train::plan_densify(in, rules, 10.0, 1);
    EXPECT_EQ(lenient.report.pruned, 1u);
    EXPECT_EQ(lenient.sources, (std::vector<uint32_t>{0, 2, 3}));

    rules.prune_large = true;  // scale 5 > 0.1 x extent 10
    EXPECT_EQ(train::plan_densify(in, rules, 10.0, 1).sources, (std::vector<uint32_t>{0, 2}));
    rules.max_screen_radius = 20;
    const auto strict = train::plan_densify(in, rules, 10.0, 1);
    EXPECT_EQ(strict.sources, (std::vector<uint32_t>{0}));
    EXPECT_EQ(strict.report.pruned, 3u);
}

TEST(Densify, TheCapKeepsTheLargestGradients) {
    DensifyRules rules;
    rules.max_gaussians = 6;  // room for two clones
    const auto plan = train::plan_densify(inputs_of({0.05f, 0.05f, 0.05f, 0.05f}, {0.001f, 0.004f, 0.003f, 0.002f}),
                                          rules, 10.0, 1);
    EXPECT_EQ(plan.report.cloned, 2u);
    EXPECT_EQ(plan.sources, (std::vector<uint32_t>{0, 1, 2, 3, 1, 2}));
}

// Summed over views, a smaller mean gradient that four more views share outranks a larger one.
TEST(Densify, TheGradientSumRanksByEveryViewThatAsks) {
    HostDensifyInputs in = inputs_of({0.05f, 0.05f}, {0.004f, 0.003f});
    in.sums[1 * train::kDensifyStride] = 0.003f * 8.0f;
    in.sums[1 * train::kDensifyStride + 1] = 8.0f;
    DensifyRules rules;
    rules.max_gaussians = 3;  // room for one clone
    EXPECT_EQ(train::plan_densify(in, rules, 10.0, 1).sources, (std::vector<uint32_t>{0, 1, 0}));
    rules.ranking = train::DensifyRanking::gradient_sum;
    EXPECT_EQ(train::plan_densify(in, rules, 10.0, 1).sources, (std::vector<uint32_t>{0, 1, 1}));
}

TEST(Densify, NotDrawnMeansNoGradient) {
    HostDensifyInputs in = inputs_of({0.05f}, {1.0f});
    in.sums[1] = 0.0f;  // no view drew it, whatever the sum says
    EXPECT_EQ(train::plan_densify(in, DensifyRules{}, 10.0, 1).report.after, 1u);
    // Nor is it a candidate when every gradient qualifies.
    DensifyRules any;
    any.grad_threshold = 0;
    EXPECT_EQ(train::plan_densify(in, any, 10.0, 1).report.after, 1u);
}

class DensifyPasses : public GpuTest {};

TEST_F(DensifyPasses, MoveParametersAndMomentsByThePlan) {
    const GaussianCloud params = random_scene(5, 4, 1, 4.0f, 6.0f, 0.05f, 0.2f, 1.5f);
    GaussianCloud first = params, second = params;
    for (auto* v : {&first.positions, &first.log_scales, &first.rotations, &first.opacity_logits, &first.sh}) {
        for (auto& x : *v) x += 1.0f;
    }
    for (auto* v : {&second.positions, &second.log_scales, &second.rotations, &second.opacity_logits, &second.sh}) {
        for (auto& x : *v) x = x * x + 2.0f;
    }
    train::TrainableScene next = train::TrainableScene::upload(context(), params, &first, &second);
    train::DensifyPlan plan;
    plan.sources = {3, 1, 1, 2, 2};  // survivors 3, 1; clone of 1; two samples of 2
    plan.fresh_from = 2;
    plan.override_from = 3;
    plan.overrides = {10, 11, 12, -1, -2, -3, 1.5f, 20, 21, 22, -4, -5, -6, 2.5f};
    train::DensifyPasses passes(context());
    passes.apply(next, plan);
    ASSERT_EQ(next.layout.count, 5u);
    const GaussianCloud p = next.download(context()), m1 = next.download(context(), next.first_moment),
                        m2 = next.download(context(), next.second_moment);
    const int sh = params.sh_coefficients() * 3;
    for (size_t j = 0; j < 5; ++j) {
        const size_t i = plan.sources[j];
        SCOPED_TRACE(j);
        for (int k = 0; k < 3; ++k) {
            const float position = j >= 3 ? plan.overrides[7 * (j - 3) + k] : params.positions[3 * i + k];
            const float log_scale = j >= 3 ? plan.overrides[7 * (j - 3) + 3 + k] : params.log_scales[3 * i + k];
            EXPECT_EQ(p.positions[3 * j + k], position);
            EXPECT_EQ(p.log_scales[3 * j + k], log_scale);
        }
        for (int k = 0; k < 4; ++k) EXPECT_EQ(p.rotations[4 * j + k], params.rotations[4 * i + k]);
        EXPECT_EQ(p.opacity_logits[j], j >= 3 ? plan.overrides[7 * (j - 3) + 6] : params.opacity_logits[i]);
        for (int k = 0; k < sh; ++k) EXPECT_EQ(p.sh[sh * j + k], params.sh[sh * i + k]);
        // Moments carry over for survivors and start at zero for new Gaussians, in every block.
        const bool fresh = j >= 2;
        EXPECT_EQ(m1.positions[3 * j + 1], fresh ? 0.0f : first.positions[3 * i + 1]);
        EXPECT_EQ(m2.rotations[4 * j + 3], fresh ? 0.0f : second.rotations[4 * i + 3]);
        EXPECT_EQ(m1.opacity_logits[j], fresh ? 0.0f : first.opacity_logits[i]);
        EXPECT_EQ(m2.sh[sh * j + sh - 1], fresh ? 0.0f : second.sh[sh * i + sh - 1]);
    }

    passes.reset_opacity(next, 0.01);
    const GaussianCloud reset = next.download(context()), reset_m1 = next.download(context(), next.first_moment);
    const float limit = std::log(0.01f / 0.99f);
    for (size_t j = 0; j < 5; ++j) {
        EXPECT_NEAR(reset.opacity_logits[j], std::min(p.opacity_logits[j], limit), 1e-6) << j;
        EXPECT_EQ(reset_m1.opacity_logits[j], 0.0f) << j;
        EXPECT_EQ(reset_m1.positions[3 * j], m1.positions[3 * j]) << j;
    }
}

// Growing a scene never holds the old and the new one whole at once: one old array (4.7 MB: 20,000
// Gaussians of 59 floats) is the most it holds beyond the new scene; holding both scenes whole
// would add the old one's three arrays.
TEST_F(DensifyPasses, HoldNoMoreThanTheLargerSceneAndOneArray) {
    const uint32_t n = 20000;
    const GaussianCloud params = random_scene(3, n, 3, 4.0f, 6.0f, 0.05f, 0.2f, 1.5f);
    train::TrainableScene scene = train::TrainableScene::upload(context(), params);
    train::DensifyPlan plan;
    for (uint32_t i = 0; i < 2 * n; ++i) plan.sources.push_back(i % n);
    plan.fresh_from = plan.override_from = 2 * n;
    train::DensifyPasses passes(context());
    const uint64_t array_bytes = uint64_t(2 * n) * 59 * sizeof(float);
    context().reset_peak_device_bytes();
    passes.apply(scene, plan);
    ASSERT_EQ(scene.layout.count, 2 * n);
    const uint64_t held = context().held_device_bytes(), peak = context().peak_device_bytes();
    EXPECT_GE(held, 3 * array_bytes);  // parameters and two moments
    // The plan's device copy stays (the next densification reuses it), so `held` counts it.
    EXPECT_LE(peak, held + array_bytes / 2 + (1u << 16)) << "one old array and alignment aside";
}

}  // namespace
}  // namespace vksplat::test
