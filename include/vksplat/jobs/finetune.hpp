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
#include <vector>

#include "vksplat/camera.hpp"
#include "vksplat/gpu/context.hpp"
#include "vksplat/io/image.hpp"
#include "vksplat/io/write_mode.hpp"
#include "vksplat/prune/quality.hpp"
#include "vksplat/render/renderer.hpp"
#include "vksplat/train/trainer.hpp"

namespace vksplat::jobs {

// The photo of a camera, composited on the background where it has alpha. Throws InputError
// naming the file when it is missing or unreadable.
using PhotoSource = std::function<io::ImageRGB(const Camera&)>;
// Photos found in a folder by camera name (io::find_image), read with io::read_image_rgb, and
// resized (area averaging) to the camera's size where `resize` is set and they differ.
PhotoSource photos_in_folder(const std::filesystem::path& images_dir, const std::array<float, 3>& background,
                             bool resize = false);

// The photo of `camera` read through `photos`: refused (InputError naming the camera) when its
// size is not the camera's.
io::ImageRGB checked_photo(const PhotoSource& photos, const Camera& camera);

// checked_photo, packed for training. A non-empty `loss_mask` (one byte per pixel, 0: the pixel
// neither counts nor pulls) must be the camera's size too.
train::Photo training_photo(const PhotoSource& photos, const Camera& camera, const std::vector<uint8_t>& loss_mask = {});

// Which pixels of a training view the loss looks at (train::Photo's mask): one byte per pixel of
// the view's camera, 0 where the pixel is left out.
using LossMasks = std::function<std::vector<uint8_t>(size_t view)>;

// The quality of a scene on the held-out views (prune::measure_quality against the photos, say).
using QualityProbe = std::function<prune::Quality(const GaussianCloud&)>;

struct FinetuneOptions {
    uint64_t iterations = 5000;
    std::vector<size_t> train_views;   // indices into the cameras; empty: every camera not a test view
    std::vector<size_t> test_views;    // held out: never stepped on; empty: default_test_views
    LossMasks loss_masks;              // empty: every pixel counts
    train::TrainOptions train;         // rates (position at its final rate by default), loss, background
    uint64_t seed = 0;                 // the order of the training views
    // Where the checkpoint lives; empty: no checkpoints (and no resume).
    std::filesystem::path checkpoint;
    uint64_t checkpoint_every = 1000;
    bool resume = false;               // continue from `checkpoint` (which must exist)
    const std::atomic<bool>* stop = nullptr;  // raised: checkpoint and return with interrupted set

    // The position rate at its final value, and the scene extent (0) found from the training
    // cameras by train::scene_extent. With PositionSchedule::decay the position rate falls from
    // its initial to its final value over this re-fit's iterations (not the reference's 30,000).
    FinetuneOptions() {
        train.position_schedule = train::PositionSchedule::final_rate;
        train.scene_extent = 0;
    }
};

struct FinetuneStatus {
    uint64_t iteration = 0, iterations = 0;
    double loss = 0;             // mean over the last steps reported
    double psnr = 0;             // of the training views stepped on since the last report
    double seconds = 0, seconds_left = 0;
    size_t gaussians = 0;
};

struct FinetuneResult {
    GaussianCloud cloud;                 // the re-fitted scene (sanitised input, Gaussians as given)
    SanitizeReport sanitize;
    std::optional<prune::Quality> before, after;  // on the test views, when a probe was given
    uint64_t iterations = 0;             // steps taken in all, a resumed run's earlier ones included
    uint64_t skipped = 0;                // of which skipped for non-finite gradients
    bool interrupted = false;            // `stop` was raised: the checkpoint holds the state, no output
    double seconds = 0;                  // wall time of this run's steps
    double gpu_ms_per_iteration = 0;     // median GPU time of a step (Vulkan timestamps)
    std::vector<StageTiming> stages;     // median GPU time of each pass
    uint64_t device_bytes = 0;           // the trainer's device memory
    std::vector<size_t> train_views, test_views;
    double scene_extent = 0;             // what the position rate was scaled by
    std::vector<size_t> distrusted_cameras;  // left out of the extent (train::scene_extent)
};

// Loads the training views' photos (checking each against its camera's size), then steps.
// Throws InputError before any step for missing or mis-sized photos, bad view indices, or a
// resume without a checkpoint.
FinetuneResult finetune_scene(const gpu::Context& context, const GaussianCloud& cloud,
                              const std::vector<Camera>& cameras, const PhotoSource& photos,
                              const FinetuneOptions& options, const QualityProbe& quality = {},
                              const std::function<void(const FinetuneStatus&)>& progress = {});

}  // namespace vksplat::jobs
