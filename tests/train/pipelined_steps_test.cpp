// Trainer::submit prepares a step while the one before runs: the same steps as Trainer::step,
// byte for byte, with every result kept in order, through overflowed frames, densification, a
// view of another size and the blend backward's timing of both forms; the training loop's use.
#include "train/checkpoint_file.hpp"  // first: its volk must come before the public headers' Vulkan
#include "train/parameter_layout.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "support/gpu_fixture.hpp"
#include "support/scenes.hpp"
#include "vksplat/io/image.hpp"
#include "vksplat/render/renderer.hpp"
#include "vksplat/train/strategy.hpp"
#include "vksplat/train/trainer.hpp"
#include "vksplat/train/training_loop.hpp"

namespace vksplat::test {
namespace {

namespace fs = std::filesystem;

class PipelinedSteps : public GpuTest {
protected:
    // row_of_five_views() (48 x 40) and, last, the first of them at 96 x 80, each with its render
    // of a generated scene as its photo.
    PipelinedSteps() {
        cameras = row_of_five_views();
        cameras.push_back(cameras[0].resized(96, 80));
        cameras.back().name = "view_0_large";
        Renderer renderer(context());
        renderer.set_scene(random_scene(7, 30, 1, 4.0f, 6.0f, 0.05f, 0.2f, 1.0f));
        for (const Camera& camera : cameras) {
            const RenderOutput out = renderer.render(camera);
            photos.push_back(train::Photo::from_image(io::ImageRGB{out.width, out.height, out.rgb}));
        }
    }
    // The view of step i: round the row, and two steps of the larger view in every seven.
    size_t view(int i) const { return i % 7 >= 5 ? cameras.size() - 1 : size_t(i) % (cameras.size() - 1); }

    std::vector<Camera> cameras;
    std::vector<train::Photo> photos;
};

bool same_bytes(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// A run of each kind on the same start: fixed-point sums, so that the order of additions cannot
// tell them apart. The start's large splats overflow the first tile entries (the step in flight
// runs again, the step recorded meanwhile is recorded again), as do the first step of the larger
// view and the first after densification has cloned every Gaussian; the position rate decays and
// the SH degree rises within the run; MCMC's noise is seeded by the step.
TEST_F(PipelinedSteps, GiveTheSynchronousStepsBytes) {
    if (!context().info().int64_atomics) GTEST_SKIP() << "no 64-bit buffer atomics on this device";
    constexpr int kSteps = 24, kDensifyAfter = 12;
    GaussianCloud start = random_scene(3, 24, 1, 4.0f, 6.0f, 0.05f, 0.2f, 1.0f);
    for (auto& s : start.log_scales) s = std::log(0.6f);
    train::TrainOptions options;
    options.deterministic = true;
    options.sh_degree = 0;
    options.rates.position_decay_steps = kSteps;
    options.position_noise = 1e4;
    train::DensifyRules rules;
    rules.grad_threshold = 1e-12;  // every Gaussian drawn qualifies,
    rules.percent_dense = 1e3;     // and is cloned

    const auto run = [&](bool pipelined) {
        train::Trainer trainer(context(), start, options);
        std::vector<train::StepResult> results;
        const auto take = [&] {
            for (auto& result : trainer.take_results()) results.push_back(std::move(result));
        };
        for (int i = 0; i < kSteps; ++i) {
            if (i == kDensifyAfter) {
                EXPECT_GT(trainer.densify(rules).after, start.size());
            }
            if (i == kSteps / 3) trainer.set_sh_degree(1);
            const size_t v = view(i);
            if (pipelined) {
                trainer.submit(cameras[v], photos[v]);
                take();
            } else {
                results.push_back(trainer.step(cameras[v], photos[v]));
            }
        }
        trainer.finish();
        take();
        EXPECT_TRUE(trainer.take_results().empty());
        EXPECT_EQ(trainer.iteration(), uint64_t(kSteps));
        return std::make_pair(trainer.cloud(), results);
    };
    const auto [synchronous, synchronous_results] = run(false);
    const auto [pipelined, pipelined_results] = run(true);

    // The run met what it is meant to: overflows of steps followed by one of the same size.
    ASSERT_EQ(synchronous_results.size(), size_t(kSteps));
    EXPECT_GT(synchronous_results[0].attempts, 1u);
    EXPECT_GT(synchronous_results[5].attempts, 1u);
    EXPECT_GT(synchronous_results[kDensifyAfter].attempts, 1u);

    ASSERT_EQ(pipelined_results.size(), size_t(kSteps));  // one result per step, none lost
    for (int i = 0; i < kSteps; ++i) {
        EXPECT_EQ(pipelined_results[i].loss, synchronous_results[i].loss) << "step " << i;
        EXPECT_EQ(pipelined_results[i].attempts, synchronous_results[i].attempts) << "step " << i;
        EXPECT_TRUE(pipelined_results[i].applied) << "step " << i;
    }
    EXPECT_TRUE(same_bytes(pipelined.positions, synchronous.positions));
    EXPECT_TRUE(same_bytes(pipelined.log_scales, synchronous.log_scales));
    EXPECT_TRUE(same_bytes(pipelined.rotations, synchronous.rotations));
    EXPECT_TRUE(same_bytes(pipelined.opacity_logits, synchronous.opacity_logits));
    EXPECT_TRUE(same_bytes(pipelined.sh, synchronous.sh));
}

// Small splats ahead of forward_camera and, 3 units to its left, 24 large ones: seen from the
// origin looking left (96 x 80) they cover the view, far more tile entries than a trainer starts
// with (4 a Gaussian), while the straight view of the same size fits them.
struct OverflowingView {
    GaussianCloud start = random_scene(3, 24, 1, 4.0f, 6.0f, 0.05f, 0.2f, 1.0f);
    Camera left = Camera::look_at({0.0, 0.0, 0.0}, {-3.0, 0.0, 0.0}, {0.0, -1.0, 0.0}, 96, 80, 80.0, 80.0);
    Camera straight = forward_camera(96, 80, 80.0);
    OverflowingView() {
        for (int k = 0; k < 24; ++k)
            add_splat(start, {.position = {-3.0, 0.1 * (k % 5) - 0.2, 0.1 * (k / 5) - 0.25},
                              .scale = {0.6, 0.6, 0.6},
                              .opacity = 0.3,
                              .color = {0.2 + 0.03 * k, 0.5, 0.8 - 0.03 * k}});
    }
};

// A step whose frame overflowed runs again: its first attempt adds nothing to the densification
// sums, which would otherwise count the step twice.
TEST_F(PipelinedSteps, AnOverflowedAttemptAddsNothingToTheDensificationSums) {
    const OverflowingView scene;
    train::Trainer trainer(context(), scene.start, {});
    const train::Photo dark{96, 80, std::vector<uint32_t>(96 * 80, 0xff102030u)};
    EXPECT_GT(trainer.step(scene.left, dark).attempts, 1u);
    const fs::path path = fs::temp_directory_path() / "vksplat_overflow_sums.checkpoint";
    trainer.save_checkpoint(path);
    const train::CheckpointData data = train::read_checkpoint(path, {});
    fs::remove(path);
    size_t counted = 0;
    for (size_t i = 0; i < trainer.size(); ++i) {
        const float views = data.densify_sums[i * train::kDensifyStride + 1];
        EXPECT_LE(views, 1.0f) << "Gaussian " << i;
        counted += views == 1.0f;
    }
    EXPECT_GE(counted, 24u) << "the large splats were drawn";
}

// A step queued behind one that overflows runs after that one has run again, as it would have
// without the queue: the looking-left step overflows; the straight step, queued behind it, fits,
// and would otherwise update the scene first (Adam's moments then see the gradients in the other
// order). Fixed-point sums, so that the order of additions cannot tell the runs apart.
TEST_F(PipelinedSteps, AStepQueuedBehindAnOverflowRunsAfterIt) {
    if (!context().info().int64_atomics) GTEST_SKIP() << "no 64-bit buffer atomics on this device";
    const OverflowingView scene;
    const train::Photo dark{96, 80, std::vector<uint32_t>(96 * 80, 0xff102030u)};
    const std::vector<const Camera*> order = {&scene.left, &scene.straight, &scene.straight, &scene.left,
                                              &scene.straight};
    train::TrainOptions options;
    options.deterministic = true;
    const auto run = [&](bool pipelined) {
        train::Trainer trainer(context(), scene.start, options);
        std::vector<train::StepResult> results;
        for (const Camera* camera : order) {
            if (pipelined) {
                trainer.submit(*camera, dark);
                for (auto& result : trainer.take_results()) results.push_back(std::move(result));
            } else {
                results.push_back(trainer.step(*camera, dark));
            }
        }
        trainer.finish();
        for (auto& result : trainer.take_results()) results.push_back(std::move(result));
        return std::make_pair(trainer.cloud(), results);
    };
    const auto [synchronous, synchronous_results] = run(false);
    const auto [pipelined, pipelined_results] = run(true);
    ASSERT_EQ(synchronous_results.size(), order.size());
    EXPECT_GT(synchronous_results[0].attempts, 1u) << "the looking-left view must overflow";
    EXPECT_EQ(synchronous_results[1].attempts, 1u) << "the straight view must fit the entries it started with";
    ASSERT_EQ(pipelined_results.size(), order.size());
    for (size_t i = 0; i < order.size(); ++i) {
        EXPECT_EQ(pipelined_results[i].loss, synchronous_results[i].loss) << "step " << i;
        EXPECT_EQ(pipelined_results[i].attempts, synchronous_results[i].attempts) << "step " << i;
    }
    EXPECT_TRUE(same_bytes(pipelined.positions, synchronous.positions));
    EXPECT_TRUE(same_bytes(pipelined.opacity_logits, synchronous.opacity_logits));
    EXPECT_TRUE(same_bytes(pipelined.sh, synchronous.sh));
}

// Whatever reads or changes the scene on the device first waits for the step in flight (whose
// commands use the scene's buffers and which may still have to run again), keeping its result.
TEST_F(PipelinedSteps, WhatReadsOrChangesTheSceneWaitsForTheStepInFlight) {
    const fs::path checkpoint = fs::temp_directory_path() / "vksplat_pipelined_steps.checkpoint";
    train::Trainer trainer(context(), random_scene(3, 24, 1, 4.0f, 6.0f, 0.05f, 0.2f, 1.0f), {});
    const std::vector<std::pair<std::string, std::function<void()>>> calls = {
        {"densify", [&] { trainer.densify({}); }},
        {"relocate", [&] { trainer.relocate({}); }},
        {"remove", [&] { trainer.remove(std::vector<uint8_t>(trainer.size(), 1)); }},
        {"reset_opacity", [&] { trainer.reset_opacity(); }},
        {"cloud", [&] { trainer.cloud(); }},
        {"save_checkpoint", [&] { trainer.save_checkpoint(checkpoint); }},
        {"finish", [&] { trainer.finish(); }},
    };
    for (size_t i = 0; i < calls.size(); ++i) {
        trainer.submit(cameras[i % 5], photos[i % 5]);
        EXPECT_TRUE(trainer.take_results().empty()) << calls[i].first;
        calls[i].second();
        EXPECT_EQ(trainer.take_results().size(), 1u) << calls[i].first;
    }
    fs::remove(checkpoint);
}

// The loop counts each step's result as it arrives, one step late; the last one's before the loop
// reports the last step and returns, and none is left behind.
TEST_F(PipelinedSteps, TheTrainingLoopCountsTheLastStep) {
    train::Trainer trainer(context(), random_scene(3, 24, 1, 4.0f, 6.0f, 0.05f, 0.2f, 1.0f), {});
    train::RefitStrategy strategy;
    std::map<size_t, train::Photo> row;
    for (size_t v = 0; v < 5; ++v) row.emplace(v, photos[v]);
    std::vector<train::LoopStatus> reported;
    train::LoopOptions options;
    options.iterations = 1;
    const train::LoopResult result =
        train::run_training_loop(trainer, strategy, cameras, {0, 1, 2, 3, 4}, row, options,
                                 [&](const train::LoopStatus& status) { reported.push_back(status); });
    ASSERT_EQ(reported.size(), 1u);
    EXPECT_EQ(reported[0].iteration, 1u);
    EXPECT_GT(reported[0].loss, 0.0);
    EXPECT_FALSE(result.stages.empty());
    EXPECT_TRUE(trainer.take_results().empty());
}

// `fastest` times both forms of the blend backward from the steps' own timestamps. The step in
// flight is timed after the next is recorded, perhaps in the other form: each form is still timed
// until it has its trials (a step timed as the form recorded last would settle the choice early).
TEST_F(PipelinedSteps, TimeBothBlendBackwardForms) {
    train::Trainer trainer(context(), random_scene(3, 24, 1, 4.0f, 6.0f, 0.05f, 0.2f, 1.0f), {});
    size_t per_pixel = 0, per_splat = 0;
    for (int i = 0; trainer.blend_backward() == train::BlendBackward::fastest; ++i) {
        ASSERT_LT(i, 40) << "still timing";
        trainer.submit(cameras[view(i)], photos[view(i)]);
        for (const auto& result : trainer.take_results())
            for (const auto& stage : result.stages) {
                per_pixel += stage.stage == "blend backward (per pixel)";
                per_splat += stage.stage == "blend backward (per splat)";
            }
    }
    EXPECT_GE(per_pixel, 10u);
    EXPECT_GE(per_splat, 10u);
}

}  // namespace
}  // namespace vksplat::test
