// Cluster pruning through a work folder: each stage reads what the stages before it saved.
#include "vksplat/jobs/cluster_work_dir.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <regex>

#include "jobs/log_line.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/io/image.hpp"
#include "vksplat/io/npy.hpp"
#include "vksplat/jobs/view_selection.hpp"
#include "vksplat/prune/selection.hpp"

namespace vksplat::jobs {
namespace {

namespace fs = std::filesystem;

std::string view_stem(size_t view) {
    char name[32];
    std::snprintf(name, sizeof(name), "view_%04zu", view);
    return name;
}

// Columns of cluster_scores.npy (see cluster_work_dir.hpp).
constexpr size_t kScoreColumns = 9;

fs::path regions_dir(const ClusterStageIo& io) { return io.work / "regions"; }
fs::path projection_file(const ClusterStageIo& io) { return io.work / "projection.npy"; }
fs::path projection_views_file(const ClusterStageIo& io) { return io.work / "projection_views.npy"; }
fs::path contribution_file(const ClusterStageIo& io) { return io.work / "contribution.npy"; }
fs::path clusters_file(const ClusterStageIo& io) { return io.work / "clusters.npy"; }
fs::path scores_file(const ClusterStageIo& io) { return io.work / "cluster_scores.npy"; }

void require(const fs::path& path, const char* stage) {
    if (!fs::exists(path))
        throw InputError(path.string(), std::string("not found: run `vksplat cluster ") + stage + "` first");
}

// The region map made elsewhere for a camera, by view number or by image name.
cluster::RegionMap import_map(const fs::path& dir, size_t view, const Camera& camera) {
    const std::string stems[] = {view_stem(view), fs::path(camera.name).stem().string()};
    for (const auto& stem : stems)
        for (const char* extension : {".npy", ".png"})
            if (fs::exists(dir / (stem + extension))) return cluster::read_region_map(dir / (stem + extension));
    throw InputError(dir.string(), "holds no region map for view " + std::to_string(view) + " (looked for " +
                                       stems[0] + ".npy|.png and " + stems[1] + ".npy|.png)");
}

// The saved maps, with the filter's verdict on each under `options`.
std::vector<RegionView> load_region_views(const ClusterOptions& options, const ClusterStageIo& io) {
    const fs::path dir = regions_dir(io);
    require(dir, "regions");
    std::vector<RegionView> views;
    const std::regex name("view_([0-9]+)\\.npy");
    std::smatch match;
    for (const auto& entry : fs::directory_iterator(dir)) {
        const std::string file = entry.path().filename().string();
        if (!std::regex_match(file, match, name)) continue;
        RegionView view;
        view.view = std::stoul(match[1].str());
        view.map = cluster::read_region_map(entry.path());
        const fs::path render = dir / (view_stem(view.view) + ".png");
        require(render, "regions");
        const io::ImageRGB image = io::read_image_rgb(render, options.settings.background);
        if (image.width != view.map.width || image.height != view.map.height)
            throw InputError(render.string(), "is not the size of " + entry.path().string());
        view.quality = cluster::assess_view(view.map, image.rgb, options.filter);
        views.push_back(std::move(view));
    }
    if (views.empty()) throw InputError(dir.string(), "holds no view_NNNN.npy region maps");
    std::sort(views.begin(), views.end(), [](const RegionView& a, const RegionView& b) { return a.view < b.view; });
    return views;
}

cluster::ViewLabels load_labels(size_t gaussians, const ClusterStageIo& io, std::vector<size_t>* views) {
    require(projection_file(io), "project");
    const io::NpyArray array = io::read_npy(projection_file(io));
    if (array.shape.size() != 2 || array.shape[1] != gaussians)
        throw InputError(projection_file(io).string(), "is not [views, " + std::to_string(gaussians) +
                                                           "] (made for another scene?)");
    cluster::ViewLabels labels;
    labels.views = array.shape[0];
    labels.gaussians = gaussians;
    if (array.dtype == io::NpyDtype::int16) {
        const auto values = array.values<int16_t>();
        labels.ids.assign(values.begin(), values.end());
    } else {
        labels.ids = array.values<int32_t>();
    }
    if (views) {
        require(projection_views_file(io), "project");
        const auto ids = io::read_npy(projection_views_file(io)).values<int32_t>();
        if (ids.size() != labels.views)
            throw InputError(projection_views_file(io).string(), "does not match projection.npy");
        views->assign(ids.begin(), ids.end());
    }
    return labels;
}

std::vector<int32_t> load_clusters(size_t gaussians, const ClusterStageIo& io) {
    require(clusters_file(io), "build");
    auto ids = io::read_npy(clusters_file(io)).values<int32_t>();
    if (ids.size() != gaussians)
        throw InputError(clusters_file(io).string(), "holds " + std::to_string(ids.size()) + " ids, the scene has " +
                                                         std::to_string(gaussians) + " Gaussians");
    return ids;
}

// Work folders from before the contribution term have none: only the original G* (kappa 0) can
// be scored from them.
std::vector<float> load_contribution(size_t gaussians, const cluster::ScoreWeights& weights, const ClusterStageIo& io) {
    if (!fs::exists(contribution_file(io))) {
        if (weights.kappa == 0) return {};
        throw InputError(contribution_file(io).string(),
                         "not found: run `vksplat cluster project` again (with --force) to make it, or give "
                         "--kappa 0 for the original G*");
    }
    auto values = io::read_npy(contribution_file(io)).values<float>();
    if (values.size() != gaussians)
        throw InputError(contribution_file(io).string(), "holds " + std::to_string(values.size()) +
                                                             " values, the scene has " + std::to_string(gaussians) +
                                                             " Gaussians");
    return values;
}

}  // namespace

void regions_stage(Renderer& renderer, const GaussianCloud& cloud, const std::vector<Camera>& cameras,
                   const ClusterOptions& options, const std::optional<fs::path>& import_dir, const ClusterStageIo& io) {
    const fs::path dir = regions_dir(io);
    fs::create_directories(dir);
    for (size_t view : region_views(cameras, options))
        for (const char* extension : {".npy", ".png"}) io::check_writable(dir / (view_stem(view) + extension), io.mode);
    if (import_dir && !fs::is_directory(*import_dir)) throw InputError(import_dir->string(), "is not a folder");
    RegionSource source;
    if (import_dir) source = [&](size_t view) { return import_map(*import_dir, view, cameras[view]); };
    const auto save = [&](const RegionView& view, const RenderOutput& image) {
        cluster::write_region_map(dir / (view_stem(view.view) + ".npy"), view.map, io.mode);
        io::write_png_rgb(dir / (view_stem(view.view) + ".png"), image.width, image.height, image.rgb.data(), 8, io.mode);
    };
    const auto views = make_region_maps(renderer, cloud, cameras, options, source, save, io.progress);
    size_t regions = 0;
    for (const auto& view : views) regions += view.quality.regions;
    say(io.log, "region maps: " + std::to_string(views.size()) + " views, " +
                    std::to_string(views.empty() ? 0 : regions / views.size()) + " regions per view on average, in " +
                    dir.string());
}

void project_stage(Renderer& renderer, const gpu::Context& context, const GaussianCloud& cloud,
                   const std::vector<Camera>& cameras, const ClusterOptions& options, const ClusterStageIo& io) {
    io::check_writable(projection_file(io), io.mode);
    io::check_writable(projection_views_file(io), io.mode);
    io::check_writable(contribution_file(io), io.mode);
    const std::vector<RegionView> regions = load_region_views(options, io);
    std::vector<const RegionView*> used;
    std::vector<int32_t> view_ids;
    for (size_t k : filter_views(regions, options, io.log)) {
        used.push_back(&regions[k]);
        view_ids.push_back(int32_t(regions[k].view));
    }
    const ProjectedViews projected = project_views(renderer, context, cloud, cameras, used, options, io.progress);
    const cluster::ViewLabels& labels = projected.labels;
    const int32_t largest = labels.ids.empty() ? 0 : *std::max_element(labels.ids.begin(), labels.ids.end());
    const std::vector<size_t> shape{labels.views, labels.gaussians};
    if (largest <= INT16_MAX) {
        const std::vector<int16_t> narrow(labels.ids.begin(), labels.ids.end());
        io::write_npy(projection_file(io), narrow.data(), shape, io.mode);
    } else {
        io::write_npy(projection_file(io), labels.ids.data(), shape, io.mode);
    }
    io::write_npy(projection_views_file(io), view_ids.data(), {view_ids.size()}, io.mode);
    io::write_npy(contribution_file(io), projected.contribution.data(), {projected.contribution.size()}, io.mode);
    const size_t seen = size_t(std::count_if(labels.ids.begin(), labels.ids.end(), [](int32_t id) { return id >= 0; }));
    char line[160];
    std::snprintf(line, sizeof(line), "projection (%s rule): %zu views x %zu Gaussians, %.1f%% of the entries in a region",
                  cluster::to_string(options.projection.rule).c_str(), labels.views, labels.gaussians,
                  labels.ids.empty() ? 0.0 : 100.0 * double(seen) / double(labels.ids.size()));
    say(io.log, line);
}

cluster::Clustering build_stage(const GaussianCloud& cloud, const ClusterOptions& options, const ClusterStageIo& io) {
    io::check_writable(clusters_file(io), io.mode);
    const cluster::ViewLabels labels = load_labels(cloud.size(), io, nullptr);
    cluster::Clustering clustering = cluster_gaussians(cloud, labels, options, io.log);
    io::write_npy(clusters_file(io), clustering.cluster_of.data(), {clustering.cluster_of.size()}, io.mode);
    return clustering;
}

cluster::ClusterScores score_stage(const GaussianCloud& cloud, const std::vector<Camera>& cameras,
                                   const ClusterOptions& options, const ClusterStageIo& io) {
    io::check_writable(scores_file(io), io.mode);
    std::vector<size_t> views;
    const cluster::ViewLabels labels = load_labels(cloud.size(), io, &views);
    const std::vector<int32_t> cluster_of = load_clusters(cloud.size(), io);
    std::vector<Camera> used;
    for (size_t view : views) {
        if (view >= cameras.size())
            throw InputError(projection_views_file(io).string(), "names view " + std::to_string(view) + " of " +
                                                                     std::to_string(cameras.size()) + " cameras");
        used.push_back(cameras[view]);
    }
    const std::vector<float> contribution = load_contribution(cloud.size(), options.weights, io);
    cluster::ClusterScores scores =
        cluster::score_clusters(cloud.positions, cluster_of, labels, used, options.weights, contribution);
    log_score_table(scores, options.weights, io.log);
    std::vector<float> table(scores.size() * kScoreColumns);
    for (size_t c = 0; c < scores.size(); ++c) {
        const double row[kScoreColumns] = {scores.spatial_raw[c], scores.depth_raw[c],      scores.spatial[c],
                                           scores.depth[c],       scores.mvr[c],            scores.score[c],
                                           scores.contribution_raw[c], scores.contribution[c], scores.centrality[c]};
        for (size_t k = 0; k < kScoreColumns; ++k) table[c * kScoreColumns + k] = float(row[k]);
    }
    io::write_npy(scores_file(io), table.data(), {scores.size(), kScoreColumns}, io.mode);
    return scores;
}

namespace {

// What stage 6 saved, checked against stage 5's clusters.
struct SavedClusterScores {
    std::vector<int32_t> cluster_of;
    cluster::ClusterScores scores;
};

SavedClusterScores load_cluster_scores(size_t gaussians, const ClusterStageIo& io) {
    SavedClusterScores saved{load_clusters(gaussians, io), {}};
    require(scores_file(io), "score");
    const io::NpyArray table = io::read_npy(scores_file(io));
    const auto values = table.values<float>();
    // 6 columns: a table from before the contribution term (G* only, no contribution limit); 8: from
    // before the centrality term. Pruning reads G* and the contributions alone.
    if (table.shape.size() != 2 || (table.shape[1] != kScoreColumns && table.shape[1] != 8 && table.shape[1] != 6))
        throw InputError(scores_file(io).string(), "is not a [clusters, " + std::to_string(kScoreColumns) + "] table");
    const size_t columns = table.shape[1];
    cluster::ClusterScores& scores = saved.scores;
    scores.score.resize(table.shape[0]);
    for (size_t c = 0; c < scores.score.size(); ++c) scores.score[c] = values[c * columns + 5];
    if (columns >= 8) {
        scores.contribution_raw.resize(table.shape[0]);
        for (size_t c = 0; c < scores.size(); ++c) scores.contribution_raw[c] = values[c * columns + 6];
    }
    for (int32_t id : saved.cluster_of)
        if (id < 0 || size_t(id) >= scores.size())
            throw InputError(clusters_file(io).string(), "names cluster " + std::to_string(id) + ", but " +
                                                             scores_file(io).string() + " scores " +
                                                             std::to_string(scores.size()) + " (re-run score)");
    return saved;
}

ClusterPruneResult write_pruned(const GaussianCloud& cloud, const std::vector<uint8_t>& keep, size_t clusters,
                                const std::vector<int32_t>& cluster_of, const fs::path& out, const ClusterStageIo& io) {
    const GaussianCloud pruned = cloud.subset(keep);
    io::write_scene(pruned, out, io.mode);
    ClusterPruneResult result;
    result.count_before = cloud.size();
    result.count_after = pruned.size();
    result.bytes_before = cloud.ply_bytes();
    result.bytes_after = fs::file_size(out);
    result.clusters = clusters;
    std::vector<uint8_t> cluster_kept(clusters, 0);
    for (size_t i = 0; i < keep.size(); ++i)
        if (keep[i]) cluster_kept[size_t(cluster_of[i])] = 1;
    result.clusters_dropped = clusters - size_t(std::count(cluster_kept.begin(), cluster_kept.end(), 1));
    return result;
}

}  // namespace

ClusterPruneResult prune_stage(const GaussianCloud& cloud, const ClusterOptions& options, const fs::path& out,
                               const ClusterStageIo& io) {
    io::check_scene_writable(out, io.mode);
    const SavedClusterScores saved = load_cluster_scores(cloud.size(), io);
    if (options.selection.max_contribution_loss < 1 && saved.scores.contribution_raw.empty())
        throw InputError(scores_file(io).string(), "has no contribution column: run `vksplat cluster score` again, "
                                                   "or give --max-contribution-loss 1");
    const cluster::ClusterSelection selection = cluster::select_clusters(saved.scores, saved.cluster_of, options.selection);
    for (const auto& warning : selection.warnings) say(io.log, "warning: " + warning);
    ClusterPruneResult result = write_pruned(cloud, selection.keep, saved.scores.size(), saved.cluster_of, out, io);
    result.contribution_dropped = selection.contribution_dropped;
    result.stopped_by_contribution = selection.stopped_by_contribution;
    return result;
}

ClusterPruneResult prune_stage_to_budget(Renderer& renderer, const GaussianCloud& cloud, const eval::TestViews& views,
                                         const prune::QualityBudget& budget, const RenderSettings& settings,
                                         const fs::path& out, const ClusterStageIo& io,
                                         const std::function<void(const prune::BudgetProbe&)>& on_probe) {
    io::check_scene_writable(out, io.mode);
    const SavedClusterScores saved = load_cluster_scores(cloud.size(), io);
    const std::vector<float> ranked_by = cluster::gaussian_scores(saved.scores, saved.cluster_of);
    const prune::Ranking ranking(ranked_by, prune::keep_all(cloud.size()));
    // Every Gaussian is a candidate, so the whole scene (a drop of 0) always meets the budget.
    prune::BudgetResult fitted = prune::fit_quality_budget(renderer, cloud, ranking, views, budget, settings, on_probe);
    ClusterPruneResult result = write_pruned(cloud, fitted.keep, saved.scores.size(), saved.cluster_of, out, io);
    result.budget = std::move(fitted);
    return result;
}

ClusterRecoverResult recover_stage(const gpu::Context& context, Renderer& renderer, const GaussianCloud& cloud,
                                   const std::vector<Camera>& cameras, const ClusterOptions& options,
                                   const PhotoSource& photos, RecoverOptions recover, const SubjectMasks& subject,
                                   const fs::path& out, const ClusterStageIo& io,
                                   const std::function<void(const train::LoopStatus&)>& progress) {
    io::check_scene_writable(out, io.mode);
    const SavedClusterScores saved = load_cluster_scores(cloud.size(), io);
    const cluster::ClusterSelection selection = cluster::select_clusters(saved.scores, saved.cluster_of, options.selection);
    for (const auto& warning : selection.warnings) say(io.log, "warning: " + warning);
    const std::vector<float> ranked_by = cluster::gaussian_scores(saved.scores, saved.cluster_of);
    const prune::KeepMask every = prune::keep_all(cloud.size());

    ClusterRecoverResult result;
    std::map<size_t, std::vector<uint8_t>> masks;
    if (subject) {
        FinetuneOptions& finetune = recover.finetune;
        finetune.train_views = split_views(cameras, finetune.test_views, finetune.train_views).train;
        RenderSettings settings;
        settings.background = finetune.train.background;
        renderer.set_scene(cloud);
        for (size_t view : finetune.train_views)
            masks[view] = subject(cameras[view], renderer.render(cameras[view], settings));
        finetune.loss_masks = [&masks](size_t view) { return masks.at(view); };
        result.masked_views = masks.size();
    }
    // The clusters chosen go whole, once: no sampling inside them, no second round.
    recover.rounds = 1;
    recover.sampled = false;
    result.recover = prune_and_recover(context, renderer, cloud, ranked_by, every, selection.gaussians_kept, cameras,
                                       photos, recover, {}, [&](int, const train::LoopStatus& s) {
                                           if (progress) progress(s);
                                       });
    const GaussianCloud& refitted = result.recover.cloud;
    io::write_scene(refitted, out, io.mode);
    result.prune.count_before = cloud.size();
    result.prune.count_after = refitted.size();
    result.prune.bytes_before = cloud.ply_bytes();
    result.prune.bytes_after = fs::file_size(out);
    result.prune.clusters = saved.scores.size();
    result.prune.clusters_dropped = selection.clusters_dropped;
    result.prune.contribution_dropped = selection.contribution_dropped;
    result.prune.stopped_by_contribution = selection.stopped_by_contribution;
    return result;
}

}  // namespace vksplat::jobs
