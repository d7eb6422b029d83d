#pragma once
// Saliency-aware cluster pruning, stage by stage (what `vksplat cluster ...` runs):
//   1 regions: render up to max_views training views, segment each into regions (or import
//     region maps made elsewhere) and assess each map for the view filter;
//   2 filter:  keep the views whose maps look like parts of a subject (cluster/view_filter.hpp);
//   3 project: region id of every Gaussian in every kept view, with occlusion (GPU);
//   4, 5 build: neighbour pairs (KD-tree) merged by union-find under the semantic constraint;
//   6 score:   spatial variance, depth variance, multi-view visibility and contribution per
//              cluster, G*;
//   7 prune:   drop the clusters of lowest G*, up to a share of the Gaussians and of the picture.
// In memory here; jobs/cluster_work_dir.hpp saves each stage's output so that later stages can
// be re-run with new parameters alone.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "vksplat/camera/camera.hpp"
#include "vksplat/cluster/cluster_scores.hpp"
#include "vksplat/cluster/projection.hpp"
#include "vksplat/cluster/region_map.hpp"
#include "vksplat/cluster/segmentation.hpp"
#include "vksplat/cluster/union_find.hpp"
#include "vksplat/cluster/view_filter.hpp"
#include "vksplat/prune/accumulate.hpp"
#include "vksplat/render/renderer.hpp"

namespace vksplat::jobs {

struct ClusterOptions {
    // Stage 1. Views: empty means the training views (all but default_test_views), thinned
    // evenly to at most max_views.
    std::vector<size_t> views;
    size_t max_views = 50;
    // Renders and built-in region maps at this fraction of the cameras' size. Half size: regions
    // are parts of the subject, tens of pixels wide, and a quarter of the pixels makes stages 1
    // and 3 (the time of the whole run) about three times faster on a CPU Vulkan driver.
    double resolution_scale = 0.5;
    RenderSettings settings;        // background and SH degree of the renders
    cluster::SegmentationParams segmentation;
    // Stage 2. Non-empty: use exactly these views (camera indices, a subset of the rendered ones)
    // instead of the filter's choice.
    cluster::ViewFilterParams filter;
    std::vector<size_t> keep_views;
    // Stage 3.
    cluster::ProjectionParams projection;
    // Stages 4-5. delta: nullopt picks it from the nearest-neighbour distances (auto_delta).
    std::optional<double> delta;
    size_t max_neighbours = 16;
    cluster::MergeRule merge;
    // Stage 6.
    cluster::ScoreWeights weights;
    // Stage 7: which clusters go (cluster_scores.hpp). The defaults drop the lowest-G* clusters
    // until half the Gaussians are gone or the next cluster would take the picture's loss past
    // max_contribution_loss, whichever comes first. The method: weights =
    // cluster::kOriginalWeights, selection.ratio = 0.9, selection.ratio_of = clusters,
    // selection.max_contribution_loss = 1.
    cluster::SelectionRule selection{
        .threshold = std::nullopt, .ratio = 0.5, .ratio_of = cluster::RatioOf::gaussians, .max_contribution_loss = 0.002};
};

// Named settings of the score and the selection (stages 6-7); the other stages' options stay as
// they are. A new user tried `cluster run` on bonsai with the defaults and got 22% dropped; the 80%
// that keeps the subject needed three options nothing pointed to:
// - whole_picture: the defaults (contribution alone; drop up to half the Gaussians while the
//   dropped paint at most 0.2% of the picture): lego -2.3% for -0.20 dB, snowmiku -14.9% for -0.14.
// - keep_subject: also weigh being central (lambda 1) and drop 80% with no limit on the picture:
//   the room goes, the subject stays (bonsai: subject -0.091 dB, 3.86 MB as SPZ; snowmiku -13.5% at
//   the defaults' cap with the subject kept exactly; lego unchanged, every Gaussian of it central).
// - original: the G* (kOriginalWeights), 90% of the clusters, no limit.
enum class ClusterPreset { whole_picture, keep_subject, original };
// "whole-picture", "keep-subject", "original"; parse_cluster_preset throws InputError listing them.
std::string_view to_string(ClusterPreset preset);
ClusterPreset parse_cluster_preset(std::string_view name);
void apply_cluster_preset(ClusterPreset preset, ClusterOptions& options);

// The automatic choice, what `vksplat cluster` does when neither a preset nor a score or selection
// option is given: keep_subject when the views do not look at most of the scene (a room around a
// subject), whole_picture otherwise. Room: the Gaussians keep_subject's score would not call
// central, centrality (cluster/centrality.hpp) under options.weights.central_threshold in the views
// stage 1 renders (region_views). Measured at 0.25 in 50 views: bonsai 80.0% room (and two
// separate groups: 1.4% of its Gaussians between 0.23 and 0.63), snowmiku 39.2% (a plush toy on a
// bed, filmed from its front half; centralities spread evenly from 0 to 0.9), lego 0.0% (its least central 0.36). Half
// lies between them: keep_subject drops 80% of the Gaussians, room first, so below half of the
// scene in the room it would drop much of the subject too (snowmiku keeps its whole-picture
// default, which drops 14.9% for -0.14 dB).
inline constexpr double kKeepSubjectFromRoomShare = 0.5;
struct ClusterPresetChoice {
    ClusterPreset preset = ClusterPreset::whole_picture;
    size_t gaussians = 0;
    size_t room = 0;   // Gaussians of centrality under central_threshold
    size_t views = 0;  // the views centrality was measured in
    double central_threshold = 0;
    double room_share() const { return gaussians ? double(room) / double(gaussians) : 0.0; }
};
ClusterPresetChoice choose_cluster_preset(const GaussianCloud& cloud, const std::vector<Camera>& cameras,
                                          const ClusterOptions& options);
// One line for the user: the choice and the numbers it was made from.
std::string describe(const ClusterPresetChoice& choice);

// Messages for the user: warnings, views dropped and why, statistics. One line per call.
using Log = std::function<void(const std::string&)>;

// Camera indices stage 1 renders.
std::vector<size_t> region_views(const std::vector<Camera>& cameras, const ClusterOptions& options);

struct RegionView {
    size_t view = 0;                // camera index
    cluster::RegionMap map;
    cluster::ViewQuality quality;   // under options.filter
};

// Where region maps come from: the built-in segmentation, or a function that returns the map
// made elsewhere for a camera index (its size sets the render's size).
using RegionSource = std::function<cluster::RegionMap(size_t view)>;

// Stage 1 (and the assessment of stage 2). `on_view` sees each view's map and render (e.g. to
// save them). Throws InputError when an imported map's aspect ratio is not its camera's.
std::vector<RegionView> make_region_maps(Renderer& renderer, const GaussianCloud& cloud,
                                         const std::vector<Camera>& cameras, const ClusterOptions& options,
                                         const RegionSource& import = {},
                                         const std::function<void(const RegionView&, const RenderOutput&)>& on_view = {},
                                         const prune::Progress& progress = {});

// Stage 2: positions in `regions` of the views to use, logging every view dropped and why. When
// the filter drops every view, all are used, with a warning (better than no evidence at all).
std::vector<size_t> filter_views(const std::vector<RegionView>& regions, const ClusterOptions& options,
                                 const Log& log);

// The camera a region map was made for: `camera` at the map's size. Throws InputError (naming
// `where`) when the aspect ratios differ by more than 1%.
Camera camera_for_map(const Camera& camera, const cluster::RegionMap& map, const std::string& where);

struct ProjectedViews {
    cluster::ViewLabels labels;
    // Per Gaussian, the share of a view's pixels it blends into (sum over the pixels of alpha * T,
    // divided by the pixel count), averaged over the views: what dropping it takes from the picture.
    std::vector<float> contribution;
};

// Stage 3: labels of every Gaussian of `cloud` in each of `views` (pointers into stage 1's output),
// and the Gaussians' contributions, from the same renders.
ProjectedViews project_views(Renderer& renderer, const gpu::Context& context, const GaussianCloud& cloud,
                                  const std::vector<Camera>& cameras, const std::vector<const RegionView*>& views,
                                  const ClusterOptions& options, const prune::Progress& progress = {});

// Stages 4-5, logging the nearest-neighbour statistics, the delta used and the cluster summary.
cluster::Clustering cluster_gaussians(const GaussianCloud& cloud, const cluster::ViewLabels& labels,
                                      const ClusterOptions& options, const Log& log);

// Prints the percentile table of the three normalised components.
void log_score_table(const cluster::ClusterScores& scores, const cluster::ScoreWeights& weights, const Log& log);

// Stages 1-6 in memory: per Gaussian, the G* of its cluster (the ranking cluster pruning keeps
// by), indexed like `cloud`; Gaussians that sanitising would drop get -infinity. Compute once and
// rank with prune::Ranking to get the keep mask of many kept counts. The renderer gets `cloud` as
// its scene.
std::vector<float> cluster_gaussian_scores(Renderer& renderer, const gpu::Context& context, const GaussianCloud& cloud,
                                           const std::vector<Camera>& cameras, const ClusterOptions& options = {},
                                           const Log& log = {});

// The cluster-pruned keep mask for a kept count: exactly min(keep_count, N) Gaussians kept,
// clusters taken whole from the best G* down (the last one partly: lower indices first).
std::vector<uint8_t> cluster_keep_mask(Renderer& renderer, const gpu::Context& context, const GaussianCloud& cloud,
                                       const std::vector<Camera>& cameras, size_t keep_count,
                                       const ClusterOptions& options = {}, const Log& log = {});

}  // namespace vksplat::jobs
