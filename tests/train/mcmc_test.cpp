// Training to a budget by 3DGS-MCMC (train::McmcStrategy): the relocation formula against a
// numerical integral, the relocation plan on the host, and on lavapipe Trainer::relocate, the
// position noise and the regularisers.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <vector>

#include "train/host_densify_inputs.hpp"
#include "train/parameter_layout.hpp"
#include "train/photographed_views.hpp"
#include "train/relocation.hpp"
#include "vksplat/train/mcmc_strategy.hpp"

namespace vksplat::test {
namespace {


// The composite of n copies at one place, integrated along an axis by the trapezoid rule:
// integral of 1 - (1 - o' exp(-x^2 / (2 s^2)))^n dx.
double composite_integral(double opacity, double scale, int copies) {
    const double step = scale / 200, end = 12 * scale;
    double sum = 0;
    for (double x = -end; x <= end; x += step)
        sum += (1.0 - std::pow(1.0 - opacity * std::exp(-x * x / (2 * scale * scale)), copies)) * step;
    return sum;
}

TEST(RelocatedCopy, CopiesRenderAsTheOriginalDid) {
    for (double opacity : {0.01, 0.3, 0.7, 0.99})
        for (int copies : {1, 2, 3, 7, 20, 51}) {
            SCOPED_TRACE(testing::Message() << "opacity " << opacity << ", copies " << copies);
            const train::RelocatedCopy copy = train::relocated_copy(opacity, copies);
            // The same opacity at the centre...
            EXPECT_NEAR(1.0 - std::pow(1.0 - copy.opacity, copies), opacity, 1e-12);
            // ...and the same profile integrated along an axis (eq. 9's aim), independently integrated.
            EXPECT_NEAR(composite_integral(copy.opacity, copy.scale_factor, copies), composite_integral(opacity, 1.0, 1),
                        1e-6 * opacity);
        }
    const train::RelocatedCopy one = train::relocated_copy(0.4, 1);
    EXPECT_DOUBLE_EQ(one.opacity, 0.4);
    EXPECT_DOUBLE_EQ(one.scale_factor, 1.0);
    EXPECT_EQ(train::relocated_copy(0.4, 80).opacity, train::relocated_copy(0.4, 51).opacity);  // the paper's table ends at 51
}

// Gaussian i at (i, 0, 0), log-scale -1, identity rotation, opacity opacities[i].
HostDensifyInputs inputs_with(const std::vector<double>& opacities) {
    const uint32_t n = uint32_t(opacities.size());
    const train::ParameterLayout layout{n, 1};
    HostDensifyInputs in(n);
    for (uint32_t i = 0; i < n; ++i) {
        in.geometry[layout.positions() + 3 * i] = float(i);
        for (int k = 0; k < 3; ++k) in.geometry[layout.log_scales() + 3 * i + k] = -1.0f;
        in.geometry[layout.rotations() + 4 * i] = 1.0f;
        in.geometry[layout.opacities() + i] = float(std::log(opacities[i] / (1 - opacities[i])));
    }
    return in;
}

double sigmoid(double x) { return 1 / (1 + std::exp(-x)); }

TEST(PlanRelocation, MovesTheTransparentAndGrowsKeepingEachPlaceAsItWas) {
    const std::vector<double> opacities = {0.5, 0.001, 0.3, 0.8, 0.004, 0.6};
    const HostDensifyInputs in = inputs_with(opacities);
    const auto [plan, report] = train::plan_relocation(in, {.min_opacity = 0.005, .target = 9}, 7);
    EXPECT_EQ(report.before, 6u);
    EXPECT_EQ(report.relocated, 2u);
    EXPECT_EQ(report.added, 3u);
    EXPECT_EQ(report.after, 9u);
    ASSERT_EQ(plan.sources.size(), 9u);
    EXPECT_EQ(plan.fresh_from, plan.override_from);
    ASSERT_EQ(plan.overrides.size(), 7 * (plan.sources.size() - plan.override_from));
    // The untouched come first, in order, and none is transparent; no copy is of a transparent one.
    for (size_t j = 0; j < plan.sources.size(); ++j) {
        EXPECT_NE(plan.sources[j], 1u);
        EXPECT_NE(plan.sources[j], 4u);
        if (j + 1 < plan.override_from) {
            EXPECT_LT(plan.sources[j], plan.sources[j + 1]);
        }
    }
    // Each live Gaussian's place composites to the opacity it had (1 - prod (1 - o_copy)), its
    // copies sit where it was, and their scales shrank by the same factor as the formula's.
    std::map<uint32_t, double> transmittance;
    for (size_t j = 0; j < plan.sources.size(); ++j) {
        const uint32_t i = plan.sources[j];
        if (j < plan.override_from) {
            transmittance[i] = 1 - opacities[i];
            continue;
        }
        const float* v = &plan.overrides[7 * (j - plan.override_from)];
        EXPECT_EQ(v[0], float(i));
        EXPECT_LE(v[3], -1.0f);
        EXPECT_GT(sigmoid(v[6]), 0.005);
        transmittance.try_emplace(i, 1.0);
        transmittance[i] *= 1 - sigmoid(v[6]);
    }
    for (const auto& [i, t] : transmittance) EXPECT_NEAR(1 - t, opacities[i], 1e-5) << i;
    // The same seed draws the same.
    EXPECT_EQ(train::plan_relocation(in, {.min_opacity = 0.005, .target = 9}, 7).plan.sources, plan.sources);
}

TEST(PlanRelocation, DrawsInProportionToOpacity) {
    std::vector<double> opacities(2002, 0.001);
    opacities[0] = 0.8;
    opacities[1] = 0.2;
    const auto [plan, report] = train::plan_relocation(inputs_with(opacities), {.min_opacity = 0.005, .target = 0}, 3);
    EXPECT_EQ(report.relocated, 2000u);
    EXPECT_EQ(report.added, 0u);
    size_t of_first = 0;
    for (uint32_t s : plan.sources) of_first += s == 0;
    EXPECT_NEAR(double(of_first) / plan.sources.size(), 0.8, 0.04);
}

TEST(PlanRelocation, LeavesASceneWithNothingAliveAsItIs) {
    const auto [plan, report] =
        train::plan_relocation(inputs_with({0.001, 0.002}), {.min_opacity = 0.005, .target = 4}, 1);
    EXPECT_EQ(report.relocated + report.added, 0u);
    EXPECT_EQ(plan.sources, (std::vector<uint32_t>{0, 1}));
}

TEST(McmcStrategy, RefusesSettingsItCannotFollow) {
    train::McmcSchedule schedule;
    EXPECT_THROW(train::McmcStrategy({}, schedule), std::invalid_argument);  // no budget
    schedule.budget = 10;
    schedule.growth = 0.9;
    EXPECT_THROW(train::McmcStrategy({}, schedule), std::invalid_argument);
}

class McmcTraining : public PhotographedViews {
protected:
    McmcTraining() : PhotographedViews(60) {}
};

// Relocation on the device: the transparent are gone, the scene grew to the target, the new
// values are the plan's, and training goes on.
TEST_F(McmcTraining, RelocateMovesTheTransparentAndGrows) {
    GaussianCloud start = truth;
    for (size_t i = 0; i < start.size(); i += 4) start.opacity_logits[i] = -9.0f;
    train::Trainer trainer(context(), start, {});
    const train::RelocationReport report = trainer.relocate({.min_opacity = 0.005, .target = 70});
    EXPECT_EQ(report.relocated, 15u);
    EXPECT_EQ(report.added, 10u);
    ASSERT_EQ(trainer.size(), 70u);
    const GaussianCloud after = trainer.cloud();
    for (size_t j = 0; j < after.size(); ++j) EXPECT_GT(sigmoid(after.opacity_logits[j]), 0.005) << j;
    EXPECT_TRUE(trainer.step(cameras[0], photos.at(0)).applied);
}

// The noise moves the nearly transparent only, the same way every run; the regularisers pull
// opacity and scale down where no view looks.
TEST_F(McmcTraining, NoiseMovesOnlyTheTransparentAndRegularisersShrinkTheUnseen) {
    GaussianCloud start = truth;
    for (size_t i = 0; i < start.size(); i += 2) start.opacity_logits[i] = -7.0f;  // opacity ~0.001
    for (size_t i = 1; i < start.size(); i += 2) start.opacity_logits[i] = 2.0f;
    // The last Gaussian far behind every camera: no view draws it.
    const size_t unseen = start.size() - 1;
    start.positions[3 * unseen + 2] = -500.0f;
    const auto train_once = [&](const train::TrainOptions& options) {
        train::Trainer trainer(context(), start, options);
        for (int s = 0; s < 3; ++s) trainer.step(cameras[size_t(s)], photos.at(size_t(s)));
        return trainer.cloud();
    };
    const GaussianCloud plain = train_once({});
    train::TrainOptions noisy;
    noisy.position_noise = 5e5;
    const GaussianCloud moved = train_once(noisy);
    EXPECT_EQ(train_once(noisy).positions, moved.positions);
    size_t transparent_moved = 0;
    for (size_t i = 0; i + 1 < start.size(); ++i) {
        const bool same = moved.positions[3 * i] == plain.positions[3 * i] &&
                          moved.positions[3 * i + 1] == plain.positions[3 * i + 1] &&
                          moved.positions[3 * i + 2] == plain.positions[3 * i + 2];
        if (i % 2) {
            EXPECT_TRUE(same) << i;  // opacity 0.88: the gate is ~e^-89
        } else {
            transparent_moved += !same;
        }
    }
    EXPECT_EQ(transparent_moved, (start.size() - 1 + 1) / 2);

    train::TrainOptions regularised;
    regularised.opacity_regularization = 0.01;
    regularised.scale_regularization = 0.01;
    const GaussianCloud pulled = train_once(regularised);
    EXPECT_EQ(plain.opacity_logits[unseen], start.opacity_logits[unseen]);
    EXPECT_LT(pulled.opacity_logits[unseen], start.opacity_logits[unseen] - 0.05f);
    for (int k = 0; k < 3; ++k) EXPECT_LT(pulled.log_scales[3 * unseen + k], start.log_scales[3 * unseen + k] - 0.01f);
}

}  // namespace
}  // namespace vksplat::test
