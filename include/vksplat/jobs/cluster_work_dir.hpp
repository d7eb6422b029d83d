#pragma once
// Cluster pruning with every stage's output saved in a work folder, so that any stage can be
// re-run with new parameters from the saved outputs of the stages before it:
//   regions/view_NNNN.npy  int32 [H, W]: region map of camera NNNN (-1: no region)
//   regions/view_NNNN.png  the render it was made from (the view filter measures its edges)
//   projection.npy         int16 (int32 if ids need it) [V, N]: region id per kept view and Gaussian
//   projection_views.npy   int32 [V]: the camera index of each row of projection.npy
//   contribution.npy       float32 [N]: per Gaussian, its mean share of the kept views' pixels
//   clusters.npy           int32 [N]: cluster id per Gaussian
//   cluster_scores.npy     float32 [C, 9]: spatial_raw, depth_raw, spatial, depth, MVR, G*,
//                          contribution_raw (sum over members), contribution (normalised), centrality
//                          per cluster
// Every stage takes the scene sanitised (sanitize()), so that all files index the same Gaussians.
#include <filesystem>
#include <optional>

#include "vksplat/io/write_mode.hpp"
#include "vksplat/jobs/cluster_prune.hpp"
#include "vksplat/jobs/prune_recover.hpp"
#include "vksplat/jobs/subject_quality.hpp"
#include "vksplat/prune/quality_budget.hpp"

namespace vksplat::jobs {

struct ClusterStageIo {
    std::filesystem::path work;
    io::WriteMode mode = io::WriteMode::refuse_existing;
    Log log;
    prune::Progress progress;
};

// Stage 1. import_dir: region maps made elsewhere, per camera as view_NNNN.npy|.png or
// <image name stem>.npy|.png; else the built-in segmentation.
void regions_stage(Renderer& renderer, const GaussianCloud& cloud, const std::vector<Camera>& cameras,
                   const ClusterOptions& options, const std::optional<std::filesystem::path>& import_dir,
                   const ClusterStageIo& io);
// Stages 2 and 3: the view filter over the saved maps and renders, then the projection.
void project_stage(Renderer& renderer, const gpu::Context& context, const GaussianCloud& cloud,
                   const std::vector<Camera>& cameras, const ClusterOptions& options, const ClusterStageIo& io);
// Stages 4 and 5.
cluster::Clustering build_stage(const GaussianCloud& cloud, const ClusterOptions& options, const ClusterStageIo& io);
// Stage 6.
cluster::ClusterScores score_stage(const GaussianCloud& cloud, const std::vector<Camera>& cameras,
                                   const ClusterOptions& options, const ClusterStageIo& io);

struct ClusterPruneResult {
    size_t count_before = 0, count_after = 0;
    size_t bytes_before = 0;      // the input as an INRIA PLY (GaussianCloud::ply_bytes)
    size_t bytes_after = 0;       // the file written
    size_t clusters = 0, clusters_dropped = 0;
    double contribution_dropped = 0;       // share of the scene's total contribution
    bool stopped_by_contribution = false;  // the contribution limit ended the drop before the ratio
    std::optional<prune::BudgetResult> budget;  // prune_stage_to_budget's probes and what it chose
};
// Stage 7: writes the pruned scene to `out`, in the format its name says (io::write_scene).
ClusterPruneResult prune_stage(const GaussianCloud& cloud, const ClusterOptions& options,
                               const std::filesystem::path& out, const ClusterStageIo& io);
// Stage 7 under a quality budget instead of options.selection: the fewest Gaussians, clusters taken
// whole from the best G* down (the last one partly, lower indices first), whose mean PSNR on
// `views` drops at most budget.max_psnr_drop (a bisection, prune/quality_budget.hpp), so the drop
// is guaranteed on those views whatever the cluster scores are worth. Writes it to `out`.
ClusterPruneResult prune_stage_to_budget(Renderer& renderer, const GaussianCloud& cloud,
                                         const eval::TestViews& views, const prune::QualityBudget& budget,
                                         const RenderSettings& settings, const std::filesystem::path& out,
                                         const ClusterStageIo& io,
                                         const std::function<void(const prune::BudgetProbe&)>& on_probe = {});

struct ClusterRecoverResult {
    ClusterPruneResult prune;     // counts and bytes of the re-fitted scene
    RecoverResult recover;        // the re-fit (one round: see recover_stage)
    size_t masked_views = 0;      // training views whose loss looked at the subject only
};
// Stage 7, then a re-fit of what it kept to the photos (jobs::prune_and_recover) in one round:
// later rounds would rank by blend significance over whole pictures, which keeps the background
// that cluster pruning just dropped. With `subject`, each training view's loss looks only at its
// subject region (from the unpruned scene's render of it), so the re-fit spends nothing on
// pixels that lost their background on purpose. Writes the re-fitted scene to `out`.
ClusterRecoverResult recover_stage(const gpu::Context& context, Renderer& renderer, const GaussianCloud& cloud,
                                   const std::vector<Camera>& cameras, const ClusterOptions& options,
                                   const PhotoSource& photos, RecoverOptions recover, const SubjectMasks& subject,
                                   const std::filesystem::path& out, const ClusterStageIo& io,
                                   const std::function<void(const train::LoopStatus&)>& progress = {});

}  // namespace vksplat::jobs
