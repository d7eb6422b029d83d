#pragma once
// The one training loop. `vksplat train`, `finetune` and `prune --recover` are configurations of
// it: a trainer (the scene and its optimiser), a strategy (strategy.hpp: SH degree, densification),
// the training views with their photos, and these options. Each step renders the next training
// view, compares it with its photo, back-propagates and steps Adam (Trainer::submit: the host
// prepares each step while the one before runs); between steps the loop checkpoints, stops when
// asked (Ctrl-C) or when steps keep being skipped (check_skipped_steps), and reports progress,
// counting each step's result as it arrives (one step late).
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "vksplat/camera/camera.hpp"
#include "vksplat/render/renderer.hpp"
#include "vksplat/train/strategy.hpp"
#include "vksplat/train/trainer.hpp"

namespace vksplat::train {

// The training view of step `iteration` (0-based): the reference walks a fresh random permutation
// of the training views each epoch. Each epoch's permutation comes from the seed and the epoch
// alone, so a resumed run continues the same order.
size_t training_view(uint64_t iteration, uint64_t seed, const std::vector<size_t>& views);

struct LoopOptions {
    uint64_t iterations = 0;            // in all: a resumed trainer's earlier steps count
    uint64_t seed = 0;                  // the order of the training views
    std::filesystem::path checkpoint;   // written every checkpoint_every steps, at the last and on stop; empty: never
    uint64_t checkpoint_every = 1000;
    const std::atomic<bool>* stop = nullptr;  // raised: checkpoint and return with interrupted set
    std::string source;                 // names the run in errors ("finetune of a.ply")
    // Called after every snapshot_every-th step (0: never) and after the last, to record how the
    // run goes; its time is not in LoopResult::seconds. Not const: one that renders may free the
    // trainer's frame first (Trainer::release_frame).
    uint64_t snapshot_every = 0;
    std::function<void(Trainer&, uint64_t iteration)> snapshot = nullptr;
};

struct LoopStatus {
    uint64_t iteration = 0, iterations = 0;
    size_t gaussians = 0;
    double loss = 0;                    // mean over the steps since the last report
    double psnr = 0;                    // of the training views stepped on since the last report
    double seconds = 0, seconds_left = 0;
};

struct LoopResult {
    uint64_t iterations = 0;            // steps taken in all, a resumed run's earlier ones included
    uint64_t skipped = 0;               // of which skipped for non-finite gradients
    bool interrupted = false;
    double seconds = 0;                 // wall time of this run's steps, the strategy's work included
    double snapshot_seconds = 0;        // spent in LoopOptions::snapshot, not in seconds
    double strategy_seconds = 0;        // of which densification and opacity resets
    SceneChangeTimes scene_changes;     // the trainer's, during this run (in seconds, not only in strategy_seconds)
    double gpu_ms_per_iteration = 0;    // median GPU time of a step (Vulkan timestamps)
    std::vector<StageTiming> stages;    // median GPU time of each pass, in recording order
    // The most device memory vksplat held on the trainer's context while the loop ran
    // (gpu::Context::peak_device_bytes, which the loop starts over): the transients of
    // densification and of snapshots' renders included, and whatever else ran on the context then.
    uint64_t peak_device_bytes = 0;
};

// Steps `trainer` until it has taken options.iterations steps. `photos` holds the photo of every
// view in `train_views` (read and checked by the caller, before any work). Progress is reported at
// most twice a second and at the last step.
LoopResult run_training_loop(Trainer& trainer, Strategy& strategy, const std::vector<Camera>& cameras,
                             const std::vector<size_t>& train_views, const std::map<size_t, Photo>& photos,
                             const LoopOptions& options, const std::function<void(const LoopStatus&)>& progress = {});

}  // namespace vksplat::train
