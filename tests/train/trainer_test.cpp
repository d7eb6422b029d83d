// The whole training step on small generated scenes: a perturbed scene re-fitted to its own
// renders recovers them on views it never trained on; bad input is refused with its name.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "support/gpu_fixture.hpp"
#include "io/io_test_helpers.hpp"
#include "support/first_format_checkpoint.hpp"
#include "support/scenes.hpp"
#include "vksplat/error.hpp"
#include "vksplat/eval/metrics.hpp"
#include "vksplat/io/image.hpp"
#include "vksplat/render/renderer.hpp"
#include "vksplat/train/scene_extent.hpp"
#include "vksplat/train/checkpoint.hpp"
#include "vksplat/train/trainer.hpp"

namespace vksplat::test {
namespace {

using io::test::expect_input_error;

// Ten views on an arc around a cluster of Gaussians at the origin; the last two are held out.
std::vector<Camera> arc_of_views(int width, int height) {
    std::vector<Camera> cameras;
    for (int i = 0; i < 10; ++i) {
        const double angle = -0.9 + 1.8 * i / 9.0;
        Camera camera = Camera::look_at({4.0 * std::sin(angle), 0.6 * std::cos(3.0 * angle), -4.0 * std::cos(angle)},
                                        {0.0, 0.0, 0.0}, {0.0, -1.0, 0.0}, width, height, 50.0, 50.0);
        camera.name = "arc_" + std::to_string(i);
        cameras.push_back(camera);
    }
    return cameras;
}

GaussianCloud cluster(uint32_t seed, size_t n) {
    GaussianCloud cloud = random_scene(seed, n, 1, 4.0f, 6.0f, 0.05f, 0.25f, 1.5f);
    for (size_t i = 0; i < n; ++i) {
        cloud.positions[3 * i + 2] -= 5.0f;                       // centred on the origin
        cloud.opacity_logits[i] = std::clamp(cloud.opacity_logits[i], -1.0f, 2.0f);
    }
    return cloud;
}

GaussianCloud perturbed(GaussianCloud cloud, uint32_t seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> noise(0.0f, 1.0f);
    for (auto& v : cloud.positions) v += 0.03f * noise(rng);
    for (auto& v : cloud.log_scales) v += 0.15f * noise(rng);
    for (auto& v : cloud.rotations) v += 0.1f * noise(rng);
    for (auto& v : cloud.opacity_logits) v += 0.4f * noise(rng);
    for (auto& v : cloud.sh) v += 0.08f * noise(rng);
    return cloud;
}

io::ImageRGB as_image(const RenderOutput& out) { return {out.width, out.height, out.rgb}; }

double mean_psnr(Renderer& renderer, const GaussianCloud& cloud, const std::vector<Camera>& cameras,
                 const std::vector<RenderOutput>& targets, const std::vector<size_t>& views) {
    renderer.set_scene(cloud);
    double sum = 0;
    for (size_t v : views) {
        const RenderOutput out = renderer.render(cameras[v]);
        sum += eval::psnr(out.rgb.data(), targets[v].rgb.data(), out.width, out.height);
    }
    return sum / double(views.size());
}

class Trainer : public GpuTest {};

TEST_F(Trainer, RecoversAPerturbedSceneOnHeldOutViews) {
    const auto cameras = arc_of_views(64, 48);
    const GaussianCloud truth = cluster(5, 80);
    Renderer renderer(context());
    renderer.set_scene(truth);
    std::vector<RenderOutput> targets;
    for (const auto& camera : cameras) targets.push_back(renderer.render(camera));
    const std::vector<size_t> train_views = {0, 1, 2, 3, 4, 5, 6, 7}, test_views = {8, 9};

    const GaussianCloud start = perturbed(truth, 11);
    const double before = mean_psnr(renderer, start, cameras, targets, test_views);
    train::TrainOptions options;
    std::vector<Camera> train_cameras;
    for (size_t v : train_views) train_cameras.push_back(cameras[v]);
    options.scene_extent = train::scene_extent(train_cameras).radius;
    train::Trainer trainer(context(), start, options);
    std::vector<train::Photo> photos;
    for (const auto& target : targets) photos.push_back(train::Photo::from_image(as_image(target)));
    std::mt19937 rng(3);
    double first_loss = 0, last_loss = 0;
    for (int i = 0; i < 400; ++i) {
        const size_t view = train_views[rng() % train_views.size()];
        const train::StepResult step = trainer.step(cameras[view], photos[view]);
        ASSERT_TRUE(step.applied) << i;
        if (i == 0) first_loss = step.loss;
        last_loss = step.loss;
    }
    const double after = mean_psnr(renderer, trainer.cloud(), cameras, targets, test_views);
    std::printf("  held-out PSNR %.2f -> %.2f dB, loss %.4f -> %.4f\n", before, after, first_loss, last_loss);
    EXPECT_LT(before, 30.0);  // the perturbation is visible
    EXPECT_GE(after, 40.0);
    EXPECT_EQ(trainer.iteration(), 400u);
    EXPECT_EQ(trainer.skipped_steps(), 0u);
}

// LearningRates::others_final: the scale, rotation, opacity and SH rates decay with the position
// rate's progress. Decayed to 1e-9 of themselves after the first step (decay over one step), the
// third step moves none of them, where at the reference's constant rates it moves all of them.
TEST_F(Trainer, OtherRatesDecayToTheirFinalMultiple) {
    const auto cameras = arc_of_views(48, 40);
    const GaussianCloud truth = cluster(5, 40);
    Renderer renderer(context());
    renderer.set_scene(truth);
    const train::Photo photo = train::Photo::from_image(as_image(renderer.render(cameras[2])));
    const GaussianCloud start = perturbed(truth, 11);
    const auto moved = [&](double others_final) {
        train::TrainOptions options;
        options.rates.position_decay_steps = 1;
        options.rates.others_final = others_final;
        train::Trainer trainer(context(), start, options);
        for (int i = 0; i < 2; ++i) trainer.step(cameras[2], photo);
        const GaussianCloud before = trainer.cloud();
        trainer.step(cameras[2], photo);
        const GaussianCloud after = trainer.cloud();
        double most = 0;
        for (size_t i = 0; i < before.opacity_logits.size(); ++i)
            most = std::max<double>(most, std::abs(after.opacity_logits[i] - before.opacity_logits[i]));
        for (size_t i = 0; i < before.log_scales.size(); ++i)
            most = std::max<double>(most, std::abs(after.log_scales[i] - before.log_scales[i]));
        for (size_t i = 0; i < before.sh.size(); ++i)
            most = std::max<double>(most, std::abs(after.sh[i] - before.sh[i]));
        return most;
    };
    EXPECT_GT(moved(1.0), 1e-3);
    EXPECT_LT(moved(1e-9), 1e-7);
}

TEST_F(Trainer, RefusesAPhotoOfTheWrongSize) {
    const auto cameras = arc_of_views(32, 24);
    train::Trainer trainer(context(), cluster(2, 10), {});
    train::Photo photo{31, 24, std::vector<uint32_t>(31 * 24, 0xffffffffu)};
    try {
        trainer.step(cameras[0], photo);
        FAIL() << "a 31x24 photo for a 32x24 camera was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("arc_0"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("31x24"), std::string::npos) << e.what();
    }
}

// Removing Gaussians (as densification and the budget's settling do) holds no more device memory
// than the larger of the steps before and after: the renderer's scene-sized buffers make room for
// the old arrays that are gathered from one at a time. Without that the peak was the old scene's
// step plus the new scene's arrays.
TEST_F(Trainer, ChangingTheSceneHoldsNoMoreThanAStep) {
    const auto cameras = arc_of_views(64, 48);
    const train::Photo photo{64, 48, std::vector<uint32_t>(64 * 48, 0xff808080u)};
    train::Trainer trainer(context(), cluster(4, 20000), {});
    trainer.step(cameras[0], photo);
    std::vector<uint8_t> keep(trainer.size(), 1);
    for (size_t i = 0; i < keep.size(); i += 10) keep[i] = 0;
    const uint64_t before = context().held_device_bytes();
    context().reset_peak_device_bytes();
    trainer.remove(keep);
    trainer.step(cameras[1], photo);
    EXPECT_EQ(trainer.size(), 18000u);
    EXPECT_LE(context().peak_device_bytes(), std::max(before, context().held_device_bytes()) + (1u << 16));
}

// Every scene change's host time lands in one of its phases, and only there: the phases a removal
// runs grow, a step that allocates nothing adds no frame time, and the step after the change,
// which allocates the frame the change freed, does.
TEST_F(Trainer, SceneChangeTimesSayWhereTheHostWaited) {
    const auto cameras = arc_of_views(64, 48);
    const train::Photo photo{64, 48, std::vector<uint32_t>(64 * 48, 0xff808080u)};
    train::Trainer trainer(context(), cluster(4, 2000), {});
    trainer.step(cameras[0], photo);
    const train::SceneChangeTimes first = trainer.scene_change_times();
    EXPECT_GT(first.frame_allocation, 0.0) << "the first step allocates its frame";
    EXPECT_EQ(first.read_back + first.plan + first.relayout, 0.0);
    trainer.step(cameras[1], photo);
    EXPECT_EQ(trainer.scene_change_times().frame_allocation, first.frame_allocation) << "nothing to allocate";
    std::vector<uint8_t> keep(trainer.size(), 1);
    keep[0] = 0;
    trainer.remove(keep);
    const train::SceneChangeTimes removed = trainer.scene_change_times();
    EXPECT_GT(removed.read_back, 0.0);
    EXPECT_GT(removed.relayout, 0.0);
    EXPECT_EQ(removed.frame_allocation, first.frame_allocation);
    trainer.step(cameras[2], photo);
    EXPECT_GT(trainer.scene_change_times().frame_allocation, removed.frame_allocation) << "the freed frame again";
}

// The blend backward's form names its stage; `fastest` tries both in turn on the first steps (the
// choice by their timings is BlendBackwardChoice's test), a form asked for is kept. The first
// step's splats cover more tiles than the first tile entries hold: its first try, cut short, is
// not a timing, and the step runs again in the same form.
TEST_F(Trainer, StagesSayWhichBlendBackwardRan) {
    const auto cameras = arc_of_views(128, 96);
    const train::Photo photo{128, 96, std::vector<uint32_t>(128 * 96, 0xff808080u)};
    GaussianCloud large = cluster(2, 10);
    for (auto& s : large.log_scales) s = std::log(0.8f);
    const auto blend_backward_stages = [&](train::BlendBackward form) {
        train::TrainOptions options;
        options.blend_backward = form;
        train::Trainer trainer(context(), large, options);
        std::vector<std::string> ran;
        for (int step = 0; step < 3; ++step) {
            const train::StepResult result = trainer.step(cameras[step], photo);
            if (step == 0) {
                EXPECT_GT(result.attempts, 1u);
            }
            for (const auto& stage : result.stages)
                if (stage.stage.starts_with("blend backward")) ran.push_back(stage.stage);
        }
        EXPECT_EQ(trainer.blend_backward(), form);  // `fastest`: still timing after 3 steps
        return ran;
    };
    const std::string per_pixel = "blend backward (per pixel)", per_splat = "blend backward (per splat)";
    EXPECT_EQ(blend_backward_stages(train::BlendBackward::fastest),
              (std::vector<std::string>{per_pixel, per_splat, per_pixel}));
    EXPECT_EQ(blend_backward_stages(train::BlendBackward::per_splat),
              (std::vector<std::string>{per_splat, per_splat, per_splat}));
}

TEST_F(Trainer, RefusesABackgroundThatIsNotAColour) {
    const auto cameras = arc_of_views(32, 24);
    train::TrainOptions options;
    options.background = {0.0f, std::nanf(""), 0.0f};
    train::Trainer trainer(context(), cluster(2, 10), options);
    train::Photo photo{32, 24, std::vector<uint32_t>(32 * 24, 0xffffffffu)};
    try {
        trainer.step(cameras[0], photo);
        FAIL() << "trained on a NaN background";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("background (0, nan, 0)"), std::string::npos) << e.what();
    }
}

TEST_F(Trainer, DropsGaussiansWithNanAttributesAndSaysSo) {
    GaussianCloud cloud = cluster(4, 12);
    cloud.positions[3] = std::nanf("");
    cloud.rotations[8] = cloud.rotations[9] = cloud.rotations[10] = cloud.rotations[11] = 0.0f;
    train::Trainer trainer(context(), cloud, {});
    EXPECT_EQ(trainer.size(), 10u);
    EXPECT_EQ(trainer.sanitize_report().dropped(), 2u);
    const auto cameras = arc_of_views(32, 24);
    Renderer renderer(context());
    renderer.set_scene(cluster(4, 12));
    const auto step = trainer.step(cameras[0], train::Photo::from_image(as_image(renderer.render(cameras[0]))));
    EXPECT_TRUE(step.applied);
    EXPECT_TRUE(std::isfinite(step.loss));
}

TEST_F(Trainer, ACheckpointResumesTheSameState) {
    const auto cameras = arc_of_views(32, 24);
    const GaussianCloud truth = cluster(8, 20);
    Renderer renderer(context());
    renderer.set_scene(truth);
    const auto photo = train::Photo::from_image(as_image(renderer.render(cameras[3])));
    train::Trainer trainer(context(), perturbed(truth, 1), {});
    for (int i = 0; i < 5; ++i) trainer.step(cameras[3], photo);
    const auto path = std::filesystem::temp_directory_path() / "vksplat_trainer_test.checkpoint";
    trainer.save_checkpoint(path);
    train::Trainer resumed(context(), path, {});
    EXPECT_EQ(resumed.iteration(), 5u);
    const GaussianCloud a = trainer.cloud(), b = resumed.cloud();
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.sh, b.sh);
    // The moments came back too: the next step moves both alike (up to float atomics' order).
    const auto step_a = trainer.step(cameras[3], photo), step_b = resumed.step(cameras[3], photo);
    EXPECT_NEAR(step_a.loss, step_b.loss, 1e-6);
    const GaussianCloud a2 = trainer.cloud(), b2 = resumed.cloud();
    for (size_t i = 0; i < a2.positions.size(); ++i) EXPECT_NEAR(a2.positions[i], b2.positions[i], 1e-5);
    std::filesystem::remove(path);

    // Not a checkpoint, or a truncated one: an error naming the file.
    const auto bad = std::filesystem::temp_directory_path() / "vksplat_trainer_test.not_a_checkpoint";
    { std::ofstream(bad) << "VKSCKPT2 but short"; }
    EXPECT_THROW(train::Trainer(context(), bad, {}), InputError);
    // The first format recorded neither its run nor the densification sums: named, not resumed.
    write_first_format_checkpoint(bad, 20, 5);
    expect_input_error([&] { train::Trainer(context(), bad, {}); }, {bad.string(), "older vksplat"});
    std::filesystem::remove(bad);
}

// A run resumed between two densifications densifies as the uninterrupted one: the sums gathered
// before the checkpoint (gradient norms, views, radii) come back with it.
TEST_F(Trainer, ACheckpointCarriesTheDensificationSums) {
    const auto cameras = arc_of_views(32, 24);
    const GaussianCloud truth = cluster(8, 20);
    Renderer renderer(context());
    renderer.set_scene(truth);
    train::Trainer trainer(context(), perturbed(truth, 2), {});
    for (int i = 0; i < 4; ++i) {
        const Camera& camera = cameras[size_t(2 * i)];
        trainer.step(camera, train::Photo::from_image(as_image(renderer.render(camera))));
    }
    const auto path = std::filesystem::temp_directory_path() / "vksplat_densify_sums.checkpoint";
    trainer.save_checkpoint(path);
    train::Trainer resumed(context(), path, {});
    std::filesystem::remove(path);

    train::DensifyRules rules;
    rules.grad_threshold = 1e-12;  // every Gaussian drawn since the last densification qualifies
    const train::DensifyReport whole = trainer.densify(rules), again = resumed.densify(rules);
    EXPECT_GT(whole.cloned + whole.split, 0u);
    EXPECT_EQ(again.cloned, whole.cloned);
    EXPECT_EQ(again.split, whole.split);
    EXPECT_EQ(again.after, whole.after);
    EXPECT_EQ(resumed.cloud().positions, trainer.cloud().positions);
}

// A checkpoint records the run it belongs to; another run's is refused, naming what differs.
TEST_F(Trainer, ACheckpointOfAnotherRunIsRefused) {
    const auto cameras = arc_of_views(32, 24);
    const GaussianCloud truth = cluster(8, 20);
    train::TrainOptions mine;
    mine.checkpoint_owner = {"finetune of a.ply", {{"scene", "0123"}, {"seed", "0"}}};
    train::Trainer trainer(context(), truth, mine);
    const auto path = std::filesystem::temp_directory_path() / "vksplat_owner.checkpoint";
    trainer.save_checkpoint(path);
    const auto header = train::read_checkpoint_header(path);
    ASSERT_TRUE(header.has_value());
    EXPECT_EQ(header->owner.fields, mine.checkpoint_owner.fields);
    EXPECT_EQ(train::Trainer(context(), path, mine).size(), truth.size());
    train::TrainOptions theirs = mine;
    theirs.checkpoint_owner = {"finetune of b.ply", {{"scene", "4567"}, {"seed", "0"}}};
    expect_input_error([&] { train::Trainer(context(), path, theirs); },
                       {path.string(), "another run (finetune of a.ply)", "its scene is 0123, this run's is 4567"});
    std::filesystem::remove(path);
    EXPECT_FALSE(train::read_checkpoint_header(path).has_value());
}

}  // namespace
}  // namespace vksplat::test
