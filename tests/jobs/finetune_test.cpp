// The re-fit job's promises about the user's files and its figures, on a small generated scene
// photographed by five views: outputs and checkpoints are checked before any step and never
// replace an input; an earlier run's checkpoint is continued only by the same run and replaced only
// when asked; a run that learns nothing fails; test views that are trained on are said to be.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "io/io_test_helpers.hpp"
#include "jobs/rendered_photos.hpp"
#include "support/first_format_checkpoint.hpp"
#include "support/gpu_fixture.hpp"
#include "support/scenes.hpp"
#include "vksplat/io/ply.hpp"
#include "vksplat/jobs/finetune.hpp"
#include "vksplat/render/renderer.hpp"
#include "vksplat/train/checkpoint.hpp"

namespace vksplat::test {
namespace {

namespace fs = std::filesystem;
using io::test::expect_input_error;
using io::test::read_bytes;
using io::test::ScratchDir;

class Finetune : public GpuTest {
protected:
    Finetune() : renderer(context()) {
        truth = random_scene(5, 40, 1, 4.0f, 6.0f, 0.05f, 0.2f, 1.0f);
        renderer.set_scene(truth);
        input = scratch / "scene.ply";
        io::write_ply(truth, input);
        options.iterations = 4;
        options.test_views = {0};
        options.checkpoint = scratch / "run.checkpoint";
        options.out = scratch / "refit.ply";
        options.inputs = {input};
        options.source = "finetune of scene.ply";
    }
    jobs::FinetuneResult run(const GaussianCloud& scene, const jobs::FinetuneOptions& o) {
        return jobs::finetune_scene(context(), scene, cameras, photos, o);
    }

    ScratchDir scratch;
    Renderer renderer;
    GaussianCloud truth;
    std::vector<Camera> cameras = row_of_five_views();
    jobs::PhotoSource photos = rendered_photos(renderer);
    fs::path input;
    jobs::FinetuneOptions options;
};

// Each refusal comes before the first step: no checkpoint is written and the input is unchanged.
TEST_F(Finetune, RefusesOutputsThatAreInputsOrCannotBeWrittenBeforeAnyStep) {
    const std::string before = read_bytes(input);
    const auto refused = [&](jobs::FinetuneOptions o, const std::vector<std::string>& parts) {
        expect_input_error([&] { run(truth, o); }, parts);
        EXPECT_FALSE(fs::exists(options.checkpoint)) << parts.front();
    };
    auto o = options;
    o.checkpoint = input;  // finetune in.ply --checkpoint in.ply
    refused(o, {input.string(), "is an input of this command"});
    o = options;
    o.checkpoint = options.out;  // --checkpoint out.ply -o out.ply
    refused(o, {options.out.string(), "is also the run's output"});
    o = options;
    o.out = input;  // -o in.ply --force
    o.mode = io::WriteMode::overwrite;
    refused(o, {input.string(), "writing over an input is refused"});
    o = options;
    o.out = scratch / "refit.xyz";
    refused(o, {"refit.xyz", "cannot write a scene as '.xyz'"});
    o = options;
    o.out = scratch / "no_such_folder" / "refit.ply";
    refused(o, {"refit.ply", "does not exist"});
    // A file of another kind at the checkpoint's path is never replaced, even when asked to.
    o = options;
    o.mode = io::WriteMode::overwrite;
    o.checkpoint = scratch / "notes.txt";
    { std::ofstream(o.checkpoint) << "the user's notes"; }
    expect_input_error([&] { run(truth, o); }, {"notes.txt", "is not a vksplat checkpoint"});
    EXPECT_EQ(read_bytes(o.checkpoint), "the user's notes");
    EXPECT_EQ(read_bytes(input), before);
}

TEST_F(Finetune, AnEarlierCheckpointIsContinuedOnlyByItsOwnRunAndReplacedOnlyWhenAsked) {
    auto first = options;
    first.out.clear();
    EXPECT_EQ(run(truth, first).iterations, 4u);
    ASSERT_TRUE(fs::exists(options.checkpoint));

    // Run again without --resume: the interrupted state is not silently replaced.
    expect_input_error([&] { run(truth, options); }, {"run.checkpoint", "holds iteration 4", "--resume", "--force"});
    // Another scene, or another recipe, cannot continue it.
    GaussianCloud other = truth.subset(std::vector<uint8_t>(truth.size(), 1));
    other.positions[0] += 0.5f;
    auto resume = options;
    resume.resume = true;
    resume.iterations = 6;
    expect_input_error([&] { run(other, resume); }, {"run.checkpoint", "made by another run", "its scene is"});
    auto white = resume;
    white.train.background = {1, 1, 1};
    expect_input_error([&] { run(truth, white); }, {"run.checkpoint", "its background is 0,0,0, this run's is 1,1,1"});
    // The same run continues where it stopped; an explicit overwrite starts over.
    EXPECT_EQ(run(truth, resume).iterations, 6u);
    auto again = options;
    again.out = scratch / "again.ply";
    again.mode = io::WriteMode::overwrite;
    EXPECT_EQ(run(truth, again).iterations, 4u);
    EXPECT_EQ(train::read_checkpoint_header(options.checkpoint)->iteration, 4u);
}

// A checkpoint of the first format, which recorded no run, is never resumed, and --force replaces
// it as it replaces any earlier run's checkpoint.
TEST_F(Finetune, AFirstFormatCheckpointIsReplacedOnlyWhenAskedAndNeverResumed) {
    write_first_format_checkpoint(options.checkpoint, truth.size(), 42);
    expect_input_error([&] { run(truth, options); }, {"holds iteration 42", "cannot be resumed", "--force"});
    auto resume = options;
    resume.resume = true;
    expect_input_error([&] { run(truth, resume); }, {"run.checkpoint", "older vksplat"});
    auto again = options;
    again.mode = io::WriteMode::overwrite;
    EXPECT_EQ(run(truth, again).iterations, 4u);
    EXPECT_TRUE(train::read_checkpoint_header(options.checkpoint)->records_run);
}

// Gaussians stretched to the sanitiser's largest log-scale along one axis overflow the backward
// pass: every step is skipped. The run fails saying so instead of writing its input back.
TEST_F(Finetune, FailsWhenStepsKeepBeingSkipped) {
    GaussianCloud needles = truth;
    for (size_t i = 0; i < needles.size(); ++i) needles.log_scales[3 * i] = 20.0f;  // clamped to kMaxLogScale
    auto o = options;
    o.iterations = 40;
    expect_input_error([&] { run(needles, o); }, {"finetune of scene.ply", "non-finite gradients", "nothing was written"});
    EXPECT_FALSE(fs::exists(o.out));
}

TEST_F(Finetune, SaysWhenTheTestViewsAreTrainedOn) {
    std::vector<std::string> notices;
    auto o = options;
    o.checkpoint.clear();
    o.out.clear();
    o.test_views = {0, 1, 2, 3, 4};  // every camera: nothing else to train on
    o.notice = [&](const std::string& line) { notices.push_back(line); };
    const jobs::FinetuneResult result = run(truth, o);
    EXPECT_FALSE(result.held_out);
    ASSERT_FALSE(notices.empty());
    EXPECT_NE(notices.front().find("not held out"), std::string::npos) << notices.front();

    o.test_views = {0};
    notices.clear();
    EXPECT_TRUE(run(truth, o).held_out);
    EXPECT_TRUE(notices.empty());
}

}  // namespace
}  // namespace vksplat::test
