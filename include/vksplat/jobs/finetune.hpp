#pragma once
// Re-fits a scene to its photos: Adam on every parameter with the reference trainer's loss and
// rates (train/trainer.hpp), one random training view per step, the test views held out and
// measured before and after. What `vksplat finetune` and `vksplat prune --recover` run.
//
// A checkpoint is written every `checkpoint_every` iterations and when `stop` is raised (Ctrl-C),
// through an atomic rename, so an interrupted run leaves the last checkpoint and no half-written
// output; `resume` continues from it (same view order, same learning rates).
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "vksplat/camera/camera.hpp"
#include "vksplat/gpu/context.hpp"
#include "vksplat/io/dataset.hpp"
#include "vksplat/io/image.hpp"
#include "vksplat/io/write_mode.hpp"
#include "vksplat/eval/quality.hpp"
#include "vksplat/render/renderer.hpp"
#include "vksplat/train/trainer.hpp"
#include "vksplat/train/training_loop.hpp"

namespace vksplat::jobs {

// The photo of a camera, composited on the background where it has alpha. Throws InputError
// naming the file when it is missing or unreadable.
using PhotoSource = std::function<io::ImageRGB(const Camera&)>;
// Photos found in a folder by camera name (io::find_image), read with io::read_image_rgb, and
// undistorted where `undistortion` (a data set's, io::Dataset) holds the camera. With a
// resolution_scale other than 1 the cameras were scaled by it (jobs::load_training_data): each photo
// must scale to its camera's size exactly (else InputError naming the file; never stretched) and is
// resized to it by area averaging.
PhotoSource photos_in_folder(const std::filesystem::path& images_dir, const std::array<float, 3>& background,
                             double resolution_scale = 1.0, io::PhotoUndistortion undistortion = {});

// The photo of `camera` read through `photos`: refused (InputError naming the camera) when its
// size is not the camera's.
io::ImageRGB checked_photo(const PhotoSource& photos, const Camera& camera);

// checked_photo, packed for training. A non-empty `loss_mask` (one byte per pixel, 0: the pixel
// neither counts nor pulls) must be the camera's size too.
train::Photo training_photo(const PhotoSource& photos, const Camera& camera, const std::vector<uint8_t>& loss_mask = {});

// Which pixels of a training view the loss looks at (train::Photo's mask): one byte per pixel of
// the view's camera, 0 where the pixel is left out.
using LossMasks = std::function<std::vector<uint8_t>(size_t view)>;

// The quality of a scene on the held-out views (eval::measure_quality against the photos, say).
using QualityProbe = std::function<eval::Quality(const GaussianCloud&)>;

struct FinetuneOptions {
    uint64_t iterations = 5000;
    // Instead of `iterations` (then not read): the seconds the steps may take, from after the photos
    // are loaded. The steps of a trainer made for the purpose and thrown away (at most 50, about 2% of
    // the budget) time a step, the budget less that becomes the iteration count (so the position
    // rate's decay ends with it), and the run stops at that count or when the time is up, whichever
    // comes first. Refused unless finite and above 0, and with `resume`.
    std::optional<double> seconds;
    std::vector<size_t> train_views;   // indices into the cameras; empty: every camera not a test view
    std::vector<size_t> test_views;    // held out: never stepped on; empty: default_test_views
    LossMasks loss_masks;              // empty: every pixel counts
    train::TrainOptions train;         // rates (position at its final rate by default), loss, background
    uint64_t seed = 0;                 // the order of the training views
    // Where the checkpoint lives; empty: no checkpoints (and no resume). It follows the rules of
    // every run's checkpoint (src/jobs/run_checkpoint.hpp): none of `inputs`, not `out`, never a
    // file of another kind; an earlier run's checkpoint is continued (resume, which checks that it
    // belongs to this scene, cameras and recipe) or replaced (mode overwrite), else refused.
    std::filesystem::path checkpoint;
    uint64_t checkpoint_every = 1000;
    bool resume = false;               // continue from `checkpoint` (which must exist)
    const std::atomic<bool>* stop = nullptr;  // raised: checkpoint and return with interrupted set

    // Where the re-fitted scene is written (io::write_scene, format by extension); checked, with
    // the checkpoint, before anything else. Empty: not written (FinetuneResult::cloud only).
    std::filesystem::path out;
    io::WriteMode mode = io::WriteMode::refuse_existing;  // for `out` and an earlier checkpoint
    std::vector<std::filesystem::path> inputs;  // files the scene and cameras came from: never written
    std::string source = "finetune";   // names the run in checkpoint messages ("finetune of a.ply")
    // Warnings and notes for the user, each a line, given before the first step (cameras left out
    // of the extent, test views that are also trained on, where a resume starts).
    std::function<void(const std::string&)> notice;

    // The position rate at its final value, and the scene extent (0) found from the training
    // cameras by train::scene_extent. With PositionSchedule::decay the position rate falls from
    // its initial to its final value over this re-fit's iterations (not the reference's 30,000).
    FinetuneOptions() {
        train.position_schedule = train::PositionSchedule::final_rate;
        train.scene_extent = 0;
    }
};


// What the loop measured (train::LoopResult: steps, skipped, time, per-pass GPU medians), and:
struct FinetuneResult : train::LoopResult {
    GaussianCloud cloud;                 // the re-fitted scene (sanitised input, Gaussians as given)
    SanitizeReport sanitize;
    std::optional<eval::Quality> before, after;  // on the test views, when a probe was given
    uint64_t device_bytes = 0;           // the trainer's device memory
    std::vector<size_t> train_views, test_views;
    bool held_out = true;                // no test view was trained on (ViewSplit::held_out)
    double scene_extent = 0;             // what the position rate was scaled by
    uint64_t planned_iterations = 0;     // with a time budget: the count its timed steps planned
};

// The iterations a time budget of `seconds` holds at `step_seconds` a step: at least 1 (a re-fit
// takes a step however short its budget), at most 2^30 (the position decay's horizon is an int).
uint64_t planned_iterations(double seconds, double step_seconds);

// Checks the output and the checkpoint, loads the training views' photos (checking each against
// its camera's size), then steps, and writes options.out. Throws InputError before any step for an
// output or checkpoint it may not write, missing or mis-sized photos, bad view indices, a resume
// without a checkpoint of this run, or a time budget it refuses (FinetuneOptions::seconds); and
// during the run when steps keep being skipped for non-finite gradients (train::check_skipped_steps).
FinetuneResult finetune_scene(const gpu::Context& context, const GaussianCloud& cloud,
                              const std::vector<Camera>& cameras, const PhotoSource& photos,
                              const FinetuneOptions& options, const QualityProbe& quality = {},
                              const std::function<void(const train::LoopStatus&)>& progress = {});

}  // namespace vksplat::jobs
