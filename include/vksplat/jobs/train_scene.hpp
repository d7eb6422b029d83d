#pragma once
// Trains a scene from photos on the GPU: the reference 3DGS recipe (Kerbl et al. 2023, train.py),
// by default in its lean form (LeanRecipe) or to a budget (DensifyStrategy). What `vksplat train` does.
//
// Data: a COLMAP folder (sparse/0 with points3D.bin, .txt or .ply; photos in images/; PINHOLE or
// SIMPLE_PINHOLE cameras, other models refused: undistort first), a NeRF-synthetic folder
// (transforms_train.json, transforms_test.json; RGBA photos composited on the background;
// 100,000 random points in [-1.3, 1.3]^3 to start from), or an INRIA cameras.json beside images/
// (held out by each entry's "split" where every entry has one, else the first 13; started from
// random points in the box the cameras see around their common focus).
// The reference recipe, each constant in TrainRecipe: SH degree raised every 1,000 iterations;
// densification every 100 iterations from 500 to 15,000 (train::DensifyRules); opacity reset every
// 3,000 (and at 500 with a white background); the position rate decaying over the whole run.
#include <array>
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vksplat/camera/camera.hpp"
#include "vksplat/gpu/context.hpp"
#include "vksplat/io/dataset.hpp"
#include "vksplat/io/write_mode.hpp"
#include "vksplat/jobs/finetune.hpp"
#include "vksplat/prune/scores.hpp"
#include "vksplat/train/budget_strategy.hpp"
#include "vksplat/train/mcmc_strategy.hpp"
#include "vksplat/train/strategy.hpp"
#include "vksplat/train/trainer.hpp"
#include "vksplat/train/training_loop.hpp"

namespace vksplat::jobs {

// How the Gaussians grow: the reference recipe (train::ReferenceStrategy), the lean recipe (the
// reference's growth in a shorter window, then settled to what carries the picture: LeanRecipe),
// or training to a budget by scheduled growth and pruning (train::BudgetStrategy) or by 3DGS-MCMC's
// relocation (train::McmcStrategy). automatic: the budget recipe when densify.max_gaussians is set,
// else the lean recipe.
enum class DensifyStrategy { automatic, reference, lean, budget, mcmc };
// "automatic", "reference", "lean", "budget", "mcmc"; parse_densify_strategy throws InputError listing them.
std::string_view to_string(DensifyStrategy strategy);
DensifyStrategy parse_densify_strategy(std::string_view name);

// The lean recipe: the reference recipe (clone, split, its prunes and opacity resets) with its
// densification window ending at densify_until, then settling (train::Settling, in budget.settle's
// rounds with its restarted position decay) to the fewest Gaussians that carry keep_share of the blend
// weight (Sum alpha T) over the training views. A scene whose densification over-fits has a long tail
// of Gaussians that carry little and keeps few; one that needs its Gaussians keeps most. H200, one run
// each, test views against the photos (benchmarks/RESULTS.md, stop 48), against the reference:
// snowmiku 28.64 dB with 125,889 Gaussians against 28.21 with 446,866; bonsai (no budget) 31.30 with
// 565,965 against 31.16 with 1,050,879; lego 37.23 with 121,570 against 37.45 with 292,160. Settling
// the reference's window of 15,000 instead gained less where the scene over-fits (snowmiku 28.31) and
// settling to 0.9 or 0.97 lost more on lego (36.12, 36.99).
struct LeanRecipe {
    uint64_t densify_until = 5000;
    double keep_share = 0.99;
};

// The reference schedule (train::ReferenceSchedule: SH degree, densification, opacity resets) and
// the run's length and data choices.
struct TrainRecipe : train::ReferenceSchedule {
    DensifyStrategy strategy = DensifyStrategy::automatic;
    // The budget recipe's growth and pruning; its budget is densify.max_gaussians and its start the
    // starting points, at most start_fraction x the budget of them (a seeded random subset).
    train::BudgetSchedule budget;
    // The budget recipe removes a weighted random sample by blend weight (prune::sampling_keys,
    // seeded by the run's seed and the count) rather than the least important: see sampling_keys.
    bool budget_sampling = false;
    // The score by which the budget recipe's pruning and settling rank the Gaussians, over the
    // training views (prune::score).
    prune::ScoreMethod budget_score = prune::ScoreMethod::blend;
    // The lean recipe's window and what its settling keeps (LeanRecipe).
    LeanRecipe lean;
    // The MCMC recipe's terms; its budget is densify.max_gaussians too, and it starts from the same
    // subset of the starting points.
    train::McmcSchedule mcmc;
    double start_fraction = 0.5;
    // The reference's rates; the position rate's decay runs over `iterations`.
    train::LearningRates rates;
    uint64_t iterations = 30000;
    uint64_t test_every = 8;            // COLMAP: every 8th photo by name is a test view (llffhold)
    size_t random_points = 100000;      // NeRF-synthetic and INRIA starts
    float random_box = 1.3f;            // NeRF-synthetic start: uniform in [-box, box]^3
};

struct TrainingData {
    std::string format;                 // "colmap", "nerf-synthetic" or "inria"
    std::vector<Camera> cameras;
    std::vector<size_t> train_views, test_views;
    GaussianCloud initial;
    std::filesystem::path images_dir;   // where the photos are found by camera name
    io::PhotoUndistortion undistortion; // for photos of COLMAP cameras with lens distortion (photos_in_folder)
    std::vector<std::string> warnings;
    std::vector<std::string> notices;   // what was done to the data, e.g. photos undistorted
    std::filesystem::path folder;       // the data folder, to name the run
    std::vector<std::filesystem::path> inputs;  // the camera and point files read: never written over
    bool held_out = true;               // no test view is also a training view (ViewSplit::held_out)
};

// Reads cameras, the split and the starting Gaussians. `resolution_scale` (0 < s <= 1) shrinks the
// cameras (the photos are resized to match when read). Throws InputError naming what is missing or wrong.
TrainingData load_training_data(const std::filesystem::path& data_dir, const TrainRecipe& recipe,
                                double resolution_scale, uint64_t seed);

struct TrainOptions {
    TrainRecipe recipe;
    std::array<float, 3> background{0, 0, 0};
    uint64_t seed = 0;
    // Device memory training may hold (0: the device's budget). Growth stops where the next
    // densification would pass it; a start that does not fit is refused before any step.
    uint64_t memory_budget = 0;
    std::filesystem::path out_dir;      // point_cloud.ply, cameras.json, metrics.json, checkpoint
    io::WriteMode mode = io::WriteMode::refuse_existing;
    uint64_t checkpoint_every = 5000;
    // From out_dir/checkpoint, which must belong to this data, cameras and recipe; without resume
    // an existing checkpoint is replaced only with mode overwrite (jobs/run_checkpoint.hpp).
    bool resume = false;
    const std::atomic<bool>* stop = nullptr;
    // Warnings and notes for the user, each a line, given before the first step.
    std::function<void(const std::string&)> notice;
    // Test PSNR measured every this many iterations (and at the last) into TrainResult::history;
    // 0: only at the end. Its time is not in the run's seconds.
    uint64_t evaluate_every = 0;
    bool deterministic = false;         // train::TrainOptions::deterministic
    train::BlendBackward blend_backward = train::BlendBackward::fastest;  // train::TrainOptions::blend_backward
};

// The run as it went: after every 500th step (and the last) the Gaussians held; where measured
// (TrainOptions::evaluate_every), the test PSNR.
struct TrainSnapshot {
    uint64_t iteration = 0;
    size_t gaussians = 0;
    std::optional<double> test_psnr;
};


// What the loop measured (train::LoopResult; its strategy_seconds is densification and opacity
// resets), and:
struct TrainResult : train::LoopResult {
    size_t gaussians = 0;
    std::string strategy;              // "reference" or "budget"
    train::ImportancePrunes importance_prunes; // what the budget or the lean recipe removed by importance
    train::McmcEvents mcmc_events;     // what the MCMC recipe moved and added
    std::vector<TrainSnapshot> history;
    double evaluate_seconds = 0;       // measuring history's test PSNR
    eval::Quality test;                // on the test views against the photos
    double scene_extent = 0;
    std::filesystem::path ply, cameras_json, metrics_json, report;  // report.html and its charts beside it
};

// A scene's quality on the test views (eval::measure_quality, say).
using TestMeasure = std::function<eval::Quality(const GaussianCloud&, const eval::TestViews&)>;

// Trains from `data` (load_training_data), the photos read through `photos` (at the cameras'
// size), and writes the outputs into options.out_dir. Refuses before the first step: outputs that
// are inputs (whatever the mode), existing outputs (unless options.mode says overwrite or the run
// resumes), a checkpoint it may not continue or replace, and missing or mis-sized photos. Stops with
// InputError when steps keep being skipped for non-finite gradients (train::check_skipped_steps).
TrainResult train_scene(const gpu::Context& context, const TrainingData& data, const PhotoSource& photos,
                        const TrainOptions& options, const TestMeasure& measure,
                        const std::function<void(const train::LoopStatus&)>& progress = {});

// What the budget and lean recipes settle by (train::Settling): options.recipe.budget_score over
// data's training views, rendered on the trainer's current Gaussians by a renderer of its own
// (sampling keys instead where recipe.budget_sampling). The function refers to `context` and
// `data`, which must outlive it.
train::Importance settling_importance(const gpu::Context& context, const TrainingData& data, const TrainOptions& options);

// The Gaussians a memory budget leaves room for: the trainer's bytes per Gaussian (parameters,
// Adam's moments, frame and per-splat buffers) against the budget less the per-pixel buffers.
size_t gaussians_within(uint64_t budget, int sh_degree, uint64_t pixels);

}  // namespace vksplat::jobs
