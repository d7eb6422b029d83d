#pragma once
// Prunes a scene: scores every Gaussian over the training views, keeps what a selector asks for
// (on top of the lossless pass, see prune/selection.hpp), measures the quality on the test views
// before and after, and writes the smaller scene. What `vksplat prune` does.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <variant>
#include <vector>

#include "vksplat/camera/camera.hpp"
#include "vksplat/io/write_mode.hpp"
#include "vksplat/jobs/prune_recover.hpp"
#include "vksplat/jobs/view_selection.hpp"
#include "vksplat/prune/accumulate.hpp"
#include "vksplat/eval/quality.hpp"
#include "vksplat/prune/quality_budget.hpp"
#include "vksplat/prune/scores.hpp"
#include "vksplat/prune/size_budget.hpp"
#include "vksplat/render/renderer.hpp"

namespace vksplat::jobs {

// How much to keep; see prune/selection.hpp for the exact rules of each.
struct DropAtOrBelow {
    float threshold = 0;
};
struct DropRatio {
    double ratio = 0;
};
struct KeepCount {
    size_t count = 0;
};
// A size budget's format is the output's (set by the job); see prune/size_budget.hpp.
using PruneSelector = std::variant<DropAtOrBelow, DropRatio, KeepCount, prune::QualityBudget, prune::SizeBudget>;

struct PruneOptions {
    // The ranking, of every re-fit round too; unset: the best measured for the job (score_method_of).
    std::optional<prune::ScoreMethod> method;
    PruneSelector selector = prune::QualityBudget{};
    std::vector<size_t> test_views;   // empty: default_test_views
    std::vector<size_t> train_views;  // empty: default_train_views
    std::optional<std::filesystem::path> images_dir;  // photos: quality is measured against them
    // Or the photos from a source of the caller's (in memory, another decoder: refit_bench reads
    // .npy on hosts without image codecs); used instead of images_dir where set.
    PhotoSource photos;
    RenderSettings settings;          // background (also composited under the photos' alpha)
    // Write SH up to this degree (capped at the scene's). A quality budget then measures its drop
    // from the unpruned scene at this degree.
    std::optional<int> sh_degree;
    // Round the written model's higher SH to this precision (prune/sh_precision.hpp: fewer bits of
    // SPZ's byte, a smaller SPZ file); a size budget measures its candidates rounded so.
    std::optional<prune::ShPrecision> sh_precision;
    uint64_t seed = 0;                // for the random method
    // Scores of `method` (float32 [N]) and the view totals (float32 [N, 5]; only where there are
    // any: rendered, or loaded from a totals file); see prune/score_files.hpp.
    std::optional<std::filesystem::path> save_scores, save_totals;
    // Either kind of file instead of rendering the training views. A scores file is taken as the
    // scores of `method` and carries no pixel counts, so the lossless pass is then skipped.
    std::optional<std::filesystem::path> load_scores;
    // Re-fit what is kept to the photos (needs images_dir or photos); see jobs/prune_recover.hpp.
    // With a QualityBudget each probe is re-fitted (one round) and the budget holds after
    // re-fitting. With a SizeBudget its shortlisted candidates are measured after a short re-fit
    // each (a tenth of the iterations; prune::SizeBudget::refit), the count chosen is reached in
    // the rounds asked for from the scene at the chosen model's SH degree, the share of bands it
    // dropped per Gaussian is dropped before the last round's re-fit and again after it (those the
    // re-fitted model needs least), and if its file then outgrows the budget its least Gaussians
    // go until it fits (prune::fit_refitted).
    std::optional<RecoverOptions> recover;
    std::filesystem::path out;        // the pruned scene, in the format its name says (io::write_scene)
    io::WriteMode mode = io::WriteMode::refuse_existing;
    // The files the scene and cameras were read from: no output may be one of them, whatever mode.
    std::vector<std::filesystem::path> inputs;
};

struct PruneResult {
    SanitizeReport sanitize;          // what sanitising the input changed (it is pruned sanitised)
    size_t count_before = 0, count_after = 0;
    size_t lossless_dropped = 0;      // by the lossless pass, included in what was dropped
    bool lossless_applied = false;    // false when scores were loaded without pixel counts
    size_t bytes_before = 0;          // the input as an INRIA PLY (GaussianCloud::ply_bytes)
    size_t bytes_after = 0;           // the file written
    int sh_degree_before = 0, sh_degree_after = 0;
    std::vector<size_t> train_views, test_views;
    double scoring_seconds = 0;       // rendering the training views with statistics (0 if loaded)
    bool against_photos = false;
    // On the test views. Before: the input against the photos (only with photos). After: the pruned
    // scene against the photos, else against the renders of the input.
    std::optional<eval::Quality> before;
    eval::Quality after;
    std::optional<prune::BudgetResult> budget;  // with a Quality- or SizeBudget selector: every probe
    // With recover and no quality budget, each round: the Gaussians it kept, and its re-fit's
    // iterations and wall time (the iterations a time budget or the fraction dropped chose are told
    // no other way). A size budget's last round kept the count chosen, before the file was fitted;
    // where the fit then cut Gaussians, one more entry, `after_fit`, is the short re-fit of what
    // was left.
    struct RecoverRoundReport {
        size_t kept = 0;
        uint64_t iterations = 0;
        double seconds = 0;
        bool after_fit = false;
    };
    std::vector<RecoverRoundReport> recover_rounds;
};

struct PruneProgress {
    prune::Progress scoring;                                  // training views rendered
    std::function<void(const prune::BudgetProbe&)> probe;    // each quality-budget probe
    // Re-fit progress (recover): round 1, 2, ...; round 0 for the short re-fits of a size budget's
    // shortlisted candidates (prune::SizeBudget::refit), one after another; kRefitAfterFit for the
    // short re-fit of what a size budget's fit left after the rounds.
    std::function<void(int round, const train::LoopStatus&)> refit;
};
inline constexpr int kRefitAfterFit = -1;

// options.method, else the ranking measured best for the job: blend weight for a model used as
// pruned, blend-mix with `recover` (RecoverOptions::method says why).
prune::ScoreMethod score_method_of(const PruneOptions& options);

// Prunes `cloud`, seen from `cameras`, and writes the result to options.out. Refuses, before any
// work, outputs that exist (unless options.mode says overwrite) and options it cannot honour.
PruneResult prune_scene(Renderer& renderer, const GaussianCloud& cloud, const std::vector<Camera>& cameras,
                        const PruneOptions& options, const PruneProgress& progress = {});

}  // namespace vksplat::jobs
