#pragma once
// Trainer: fits a scene's parameters to photos on the GPU, one view per step, with the reference
// 3DGS trainer's loss and optimiser (Kerbl et al. 2023, gaussian-splatting train.py):
//   loss = (1 - lambda) L1 + lambda (1 - SSIM), lambda = 0.2, on the rendered picture against the photo;
//   Adam over positions, log-scales, quaternions, opacity logits and SH, each group at its own rate.
// A step is one submission: forward frame, loss, backward passes, Adam. submit() prepares a step
// (copies its photo, records its commands) while the step before it runs on the GPU, queues it
// behind that one and only then waits for that one: the GPU goes from step to step without waiting
// for the host. The queue runs one step at a time; a step's result arrives when the next is
// submitted, or by finish().
//
//   gpu::Context context;
//   train::Trainer trainer(context, cloud, options);
//   for (...) {
//       trainer.submit(cameras[v], photos[v]);
//       for (const StepResult& result : trainer.take_results()) ...
//   }
//   trainer.finish();  // the last step's result joins take_results()
//   io::write_scene(out, trainer.cloud());
#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "vksplat/camera/camera.hpp"
#include "vksplat/gpu/context.hpp"
#include "vksplat/io/write_mode.hpp"
#include "vksplat/render/renderer.hpp"
#include "vksplat/scene/scene.hpp"
#include "vksplat/train/checkpoint.hpp"
#include "vksplat/train/gradients.hpp"

namespace vksplat::io {
struct ImageRGB;
}

namespace vksplat::train {

// The reference trainer's rates (arguments/__init__.py, OptimizationParams). Position rates are
// multiplied by TrainOptions::scene_extent, as the reference scales them by its cameras' extent.
struct LearningRates {
    double position_initial = 0.00016;
    double position_final = 0.0000016;
    int position_decay_steps = 30000;  // exponential (log-linear) decay from initial to final
    double sh_dc = 0.0025;             // feature_lr
    double sh_rest = 0.0025 / 20.0;    // feature_lr / 20
    double opacity = 0.025;
    double scale = 0.005;
    double rotation = 0.001;
    // The other groups' rates (scale, rotation, opacity, SH) decay log-linearly to this multiple of
    // themselves alongside the position rate's decay (1: constant, as in the reference).
    double others_final = 1.0;
};

enum class PositionSchedule {
    decay,       // the reference's schedule from position_initial to position_final (training)
    final_rate,  // position_final throughout (re-fitting a trained scene)
};

struct TrainOptions {
    LearningRates rates;
    PositionSchedule position_schedule = PositionSchedule::decay;
    double scene_extent = 1.0;           // see scene_extent() in vksplat/train/scene_extent.hpp
    double ssim_weight = 0.2;            // lambda_dssim
    std::array<float, 3> background{0.0f, 0.0f, 0.0f};
    int sh_degree = 3;                   // SH bands evaluated (capped at the scene's degree)
    // Sum the per-splat gradients in fixed point (GradientSums::fixed_point), so that a run with the
    // same inputs gives the same bytes every time; the default float atomics add in a different
    // order each step, so densification and the result drift apart between runs.
    bool deterministic = false;
    // How the blend backward divides its work; `fastest` times both forms on the first steps and
    // keeps the faster (BlendBackward). The form that ran names the step's stage, "blend backward
    // (per pixel)" or "(per splat)".
    BlendBackward blend_backward = BlendBackward::fastest;
    // 3DGS-MCMC's terms (Kheradmand et al. 2024), all 0 (off) in the reference recipe. The loss
    // gains opacity_regularization x mean opacity + scale_regularization x mean scale (over every
    // Gaussian and axis), which starves what the picture does not need; and after every step each
    // position moves by position_noise x the position rate x gate(1 - opacity) x Sigma eps
    // (shaders/train/position_noise.comp), which moves only the nearly transparent.
    double opacity_regularization = 0;
    double scale_regularization = 0;
    double position_noise = 0;
    // Written into every checkpoint; a checkpoint of another owner is refused on resume.
    CheckpointOwner checkpoint_owner;
};

// Whether the commands train, finetune and prune --recover sum gradients in fixed point
// (TrainOptions::deterministic) when not told: wherever the device has 64-bit buffer atomics. Measured
// on bonsai (H200, benchmarks/RESULTS.md) it costs 1.015x GPU time per step at 80,000 Gaussians and
// 1.09x at 400,000 (1.00x and 1.07x wall time), under the 10% at which issue 31 asked for the same
// run giving the same bytes to become the default; --fast-sums takes float atomics in any order.
bool deterministic_by_default(const gpu::Context& context);
// What a command sums gradients with, from its flags: fixed point where asked (--deterministic;
// refused later where the device cannot) or by default (deterministic_by_default), float atomics
// where asked (--fast-sums). The CLI and the benchmarks decide alike, so that a benchmark measures
// what the command runs.
bool fixed_point_sums(const gpu::Context& context, bool deterministic, bool fast_sums);

// A photo as the loss reads it: RGBA8 per pixel, r in the low byte, row-major, top row first.
// Alpha 0 masks a pixel out of the loss (it neither counts nor pulls); any other alpha counts.
struct Photo {
    int width = 0;
    int height = 0;
    std::vector<uint32_t> rgba;

    // Every pixel counts; colours rounded to 8 bits (the photos are 8-bit already).
    static Photo from_image(const io::ImageRGB& image);
    // Pixels whose mask value is 0 are masked out; mask has width * height entries.
    static Photo from_image(const io::ImageRGB& image, const std::vector<uint8_t>& mask);
};

struct StepResult {
    // false: some Gaussian's gradient was not finite; those Gaussians did not step (their
    // parameters and Adam's moments are as they were), the others did, but with fixed-point
    // sums (the default), which cannot carry a NaN to the Gaussians it reached: then no Gaussian
    // stepped. Counted as skipped.
    bool applied = true;
    double loss = 0;         // (1 - lambda) l1 + lambda (1 - ssim)
    double l1 = 0;
    double ssim = 0;
    double psnr = 0;         // of the render against the photo (counted pixels; +inf if equal)
    uint32_t visible = 0;    // splats drawn
    uint32_t tile_entries = 0;
    uint32_t attempts = 1;   // > 1 when the tile-entry buffers grew and the step re-ran
    std::vector<StageTiming> stages;  // GPU time per pass (Vulkan timestamps)
    double gpu_milliseconds = 0;
};

// The reference's densification rules (arguments/__init__.py): grow where the projected mean's NDC
// gradient averages at least grad_threshold; clone when the largest scale is at most
// percent_dense x scene extent, else split in two; remove opacity < min_opacity, and, with
// prune_large (the reference sets it after the first opacity reset), scales above
// max_world_scale x extent. The reference also names a screen-size test (radii above 20 pixels)
// but reads radii it has just zeroed, so it never removes anything; it is off here by default
// (max_screen_radius 0) because, measured on bonsai, turning it on costs 9 dB at 7,000 iterations.
// Which candidates densification keeps when the cap (DensifyRules::max_gaussians) leaves room for
// fewer than qualify.
enum class DensifyRanking {
    mean_gradient,  // the reference's criterion: the mean NDC gradient over the views that drew it
    gradient_sum,   // that gradient summed over those views: also favours what many views want moved
};

struct DensifyRules {
    double grad_threshold = 0.0002;
    double percent_dense = 0.01;
    double min_opacity = 0.005;
    bool prune_large = false;
    double max_world_scale = 0.1;
    double max_screen_radius = 0;       // > 0: with prune_large, also remove radii above it (pixels)
    size_t max_gaussians = 0;           // 0: no cap; else growth stops there, keeping the best ranked
    DensifyRanking ranking = DensifyRanking::mean_gradient;
};

struct DensifyReport {
    size_t before = 0, cloned = 0, split = 0, pruned = 0, after = 0;
};

// Host wall time spent changing the scene (densify, relocate, remove), in seconds summed over the
// trainer's life: waiting for the step in flight, reading the device's inputs back, planning on the
// host, laying the scene out anew on the device; and the frame's allocation by the steps after
// (a scene change frees the renderer's frame to make room; the first step's allocation included).
struct SceneChangeTimes {
    double wait = 0, read_back = 0, plan = 0, relayout = 0, frame_allocation = 0;
};
// Each phase's time in `later` beyond `earlier`'s: what a stretch of training added.
SceneChangeTimes operator-(const SceneChangeTimes& later, const SceneChangeTimes& earlier);
// "waiting 0.04 s, read back 0.22 s, plan 0.27 s, re-layout 0.55 s; frame allocation 0.29 s"
std::string describe(const SceneChangeTimes& times);

// 3DGS-MCMC's densification (Kheradmand et al. 2024, sec. 4.2): every Gaussian of opacity at most
// min_opacity is moved onto a live one, drawn with probability proportional to opacity; then
// copies of Gaussians drawn the same way are added until the scene holds `target` (none when it
// holds as many already). A Gaussian drawn k times and its k copies share its place with opacity
// and scales chosen so that together they render as it did (relocated_copy).
struct RelocationRules {
    double min_opacity = 0.005;
    size_t target = 0;
};

struct RelocationReport {
    size_t before = 0, relocated = 0, added = 0, after = 0;
};

class Trainer {
public:
    // Sanitises a copy of `initial` (see sanitize(); dropped Gaussians are gone from cloud()) and
    // uploads it with Adam's moments at zero. Throws InputError for an empty scene.
    Trainer(const gpu::Context& context, const GaussianCloud& initial, const TrainOptions& options);
    // Continues from a checkpoint (save_checkpoint): parameters, moments, densification sums and
    // the counters. Throws InputError naming the file if it is not a vksplat checkpoint, is
    // truncated, or belongs to another owner than options.checkpoint_owner.
    Trainer(const gpu::Context& context, const std::filesystem::path& checkpoint, const TrainOptions& options);
    ~Trainer();
    Trainer(const Trainer&) = delete;
    Trainer& operator=(const Trainer&) = delete;

    // One iteration: render `camera`, compare with `photo`, back-propagate, Adam. Throws
    // InputError if the photo's size is not the camera's. Submits the step and waits for it, so
    // its result is returned, not kept for take_results().
    StepResult step(const Camera& camera, const Photo& photo);
    // The same iteration without waiting for it: records it (the photo is copied, so the caller
    // may drop it), submits it behind the step in flight, then waits for that one and keeps its
    // result (one that overflowed its tile entries runs again first, and this one after it).
    // It runs with the SH degree and the position rate of the moment of this call. A step of
    // another image size than the one in flight waits for that one first (the buffers may grow).
    void submit(const Camera& camera, const Photo& photo);
    // Waits for the step in flight, if any, keeping its result. Every call below that reads or
    // changes the scene on the device does so first (densify, relocate, remove, reset_opacity,
    // cloud, save_checkpoint), as does the destructor (dropping the result).
    void finish();
    // The results of the steps submitted and finished since the last call, in their order.
    std::vector<StepResult> take_results();

    // Steps submitted (applied, skipped or in flight), and of those finished, those skipped for
    // non-finite gradients (StepResult::applied).
    uint64_t iteration() const;
    uint64_t skipped_steps() const;
    // The position learning rate the next step uses.
    double position_learning_rate() const;
    // The blend backward's form: the one asked for (TrainOptions::blend_backward), or the faster
    // one timed; BlendBackward::fastest while still timing.
    BlendBackward blend_backward() const;
    // SH bands evaluated from the next step on (the trainer raises it as training goes).
    void set_sh_degree(int degree);
    // The position rate's decay (PositionSchedule::decay) from the initial to the final rate runs
    // over `steps` steps from `from_iteration` on (before it, the initial rate); by default from 0
    // over LearningRates::position_decay_steps. A strategy that prunes deep into training restarts
    // it so that what is kept can move into the gaps (the re-fit's schedule).
    void set_position_decay(uint64_t from_iteration, int steps);
    // Clones, splits and prunes by the gradients gathered since the last call (see DensifyRules),
    // carrying Adam's moments over (zero for new Gaussians), then starts gathering afresh.
    DensifyReport densify(const DensifyRules& rules);
    // MCMC's relocation and growth (RelocationRules), on the device; the Gaussians drawn and their
    // copies restart Adam's moments at zero. The draws are seeded by the iteration.
    RelocationReport relocate(const RelocationRules& rules);
    // Removes every Gaussian whose keep[i] is 0 (keep has size() entries), carrying the others'
    // parameters, moments and densification sums over in their order. Returns how many were removed.
    size_t remove(const std::vector<uint8_t>& keep);
    // The reference's opacity reset: every opacity to at most `max_opacity`, its moments zeroed.
    void reset_opacity(double max_opacity = 0.01);

    const SanitizeReport& sanitize_report() const;
    const SceneChangeTimes& scene_change_times() const;
    size_t size() const;
    // The current parameters (read back from the device).
    GaussianCloud cloud() const;
    // Waits for the step in flight and frees what only a step uses (the frame, the per-splat
    // sums), which the next step allocates again: for a caller that renders with a renderer of its
    // own between steps (a settling's scoring, an evaluation), so that the two frames are not held
    // at once. The scene, Adam's moments and the loss's buffers stay.
    void release_frame();
    // Device memory its buffers hold now (parameters, Adam's moments, frame, loss). A step's and
    // densification's transients are not in it: the context's peak_device_bytes() has them.
    uint64_t device_bytes() const;
    const gpu::Context& context() const;

    // Writes parameters, moments, densification sums, counters and options.checkpoint_owner
    // through io::write_file_atomically, so an interrupted write leaves the previous checkpoint
    // intact (vksplat/train/checkpoint.hpp).
    void save_checkpoint(const std::filesystem::path& path, io::WriteMode mode = io::WriteMode::overwrite) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace vksplat::train
