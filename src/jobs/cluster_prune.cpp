// Cluster pruning in memory, stage by stage (see jobs/cluster_prune.hpp).
#include "vksplat/jobs/cluster_prune.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "jobs/log_line.hpp"
#include "vksplat/error.hpp"
#include "vksplat/jobs/prune_scene.hpp"
#include "vksplat/prune/selection.hpp"

namespace vksplat::jobs {
namespace {

std::string format(const char* pattern, auto... values) {
    char text[256];
    std::snprintf(text, sizeof(text), pattern, values...);
    return text;
}

}  // namespace

std::vector<size_t> region_views(const std::vector<Camera>& cameras, const ClusterOptions& options) {
    const size_t camera_count = cameras.size();
    std::vector<size_t> views = options.views;
    if (views.empty()) views = default_train_views(camera_count, default_test_views(cameras));
    for (size_t view : views)
        if (view >= camera_count)
            throw InputError("view " + std::to_string(view), "there are only " + std::to_string(camera_count) + " cameras");
    if (options.max_views == 0) throw InputError("--max-views", "must be at least 1");
    if (views.size() <= options.max_views) return views;
    // Evenly spread over the list, so that the views still circle the subject.
    std::vector<size_t> thinned(options.max_views);
    for (size_t k = 0; k < thinned.size(); ++k) thinned[k] = views[k * views.size() / thinned.size()];
    return thinned;
}

Camera camera_for_map(const Camera& camera, const cluster::RegionMap& map, const std::string& where) {
    const double camera_aspect = double(camera.width) / double(camera.height);
    const double map_aspect = double(map.width) / double(map.height);
    if (std::abs(map_aspect / camera_aspect - 1.0) > 0.01)
        throw InputError(where, format("is %dx%d, but camera %s is %dx%d: the aspect ratios differ", map.width,
                                       map.height, camera.name.c_str(), camera.width, camera.height));
    return camera.resized(map.width, map.height);
}

std::vector<RegionView> make_region_maps(Renderer& renderer, const GaussianCloud& cloud,
                                         const std::vector<Camera>& cameras, const ClusterOptions& options,
                                         const RegionSource& import,
                                         const std::function<void(const RegionView&, const RenderOutput&)>& on_view,
                                         const prune::Progress& progress) {
    if (!(options.resolution_scale > 0 && options.resolution_scale <= 4))
        throw InputError("--resolution-scale", "must lie in (0, 4]");
    const std::vector<size_t> views = region_views(cameras, options);
    renderer.set_scene(cloud);
    std::vector<RegionView> out;
    out.reserve(views.size());
    for (size_t done = 0; done < views.size(); ++done) {
        const size_t view = views[done];
        RegionView region;
        region.view = view;
        Camera camera;
        if (import) {
            region.map = import(view);
            camera = camera_for_map(cameras[view], region.map, "region map of view " + std::to_string(view));
        } else {
            const Camera& full = cameras[view];
            camera = full.resized(std::max(1, int(std::lround(full.width * options.resolution_scale))),
                                  std::max(1, int(std::lround(full.height * options.resolution_scale))));
        }
        const RenderOutput image = renderer.render(camera, options.settings);
        if (!import) region.map = cluster::segment_render(image.rgb, image.alpha, image.width, image.height,
                                                          options.segmentation);
        region.quality = cluster::assess_view(region.map, image.rgb, options.filter);
        if (on_view) on_view(region, image);
        out.push_back(std::move(region));
        if (progress) progress(done + 1, views.size());
    }
    return out;
}

std::vector<size_t> filter_views(const std::vector<RegionView>& regions, const ClusterOptions& options,
                                 const Log& log) {
    std::vector<size_t> kept;
    if (!options.keep_views.empty()) {
        for (size_t view : options.keep_views) {
            const auto it = std::find_if(regions.begin(), regions.end(), [&](const RegionView& r) { return r.view == view; });
            if (it == regions.end())
                throw InputError("--views: view " + std::to_string(view), "has no region map (not rendered in stage 1)");
            kept.push_back(size_t(it - regions.begin()));
        }
        say(log, format("views: %zu given by --views (filter not applied)", kept.size()));
        return kept;
    }
    for (size_t k = 0; k < regions.size(); ++k) {
        if (regions[k].quality.keep)
            kept.push_back(k);
        else
            say(log, format("view %zu dropped: %s", regions[k].view, regions[k].quality.reason.c_str()));
    }
    if (kept.empty() && !regions.empty()) {
        say(log, format("warning: the view filter dropped all %zu views; using them all, but the region maps look "
                        "unusable, so expect few or meaningless clusters",
                        regions.size()));
        for (size_t k = 0; k < regions.size(); ++k) kept.push_back(k);
    } else {
        say(log, format("views: kept %zu of %zu", kept.size(), regions.size()));
    }
    return kept;
}

ProjectedViews project_views(Renderer& renderer, const gpu::Context& context, const GaussianCloud& cloud,
                             const std::vector<Camera>& cameras, const std::vector<const RegionView*>& views,
                             const ClusterOptions& options, const prune::Progress& progress) {
    renderer.set_scene(cloud);
    cluster::Projector projector(context);
    ProjectedViews out;
    std::vector<double> contribution(cloud.size(), 0.0);
    cluster::ViewLabels& labels = out.labels;
    labels.views = views.size();
    labels.gaussians = cloud.size();
    labels.ids.reserve(labels.views * labels.gaussians);
    for (size_t done = 0; done < views.size(); ++done) {
        const RegionView& view = *views[done];
        if (view.view >= cameras.size())
            throw InputError("view " + std::to_string(view.view), "there are only " + std::to_string(cameras.size()) + " cameras");
        const Camera camera = camera_for_map(cameras[view.view], view.map, "region map of view " + std::to_string(view.view));
        const GaussianStats stats = renderer.render_stats(camera, options.settings);
        const std::vector<int32_t> ids = projector.project(stats, view.map, options.projection);
        labels.ids.insert(labels.ids.end(), ids.begin(), ids.end());
        const double pixels = double(camera.width) * double(camera.height);
        for (size_t g = 0; g < contribution.size(); ++g) contribution[g] += stats.blend_weight[g] / pixels;
        if (progress) progress(done + 1, views.size());
    }
    out.contribution.resize(contribution.size());
    const double view_count = double(std::max<size_t>(1, views.size()));
    for (size_t g = 0; g < contribution.size(); ++g) out.contribution[g] = float(contribution[g] / view_count);
    return out;
}

cluster::Clustering cluster_gaussians(const GaussianCloud& cloud, const cluster::ViewLabels& labels,
                                      const ClusterOptions& options, const Log& log) {
    const std::vector<float>& positions = cloud.positions;
    const cluster::NearestDistanceStats nearest = cluster::nearest_distance_stats(positions);
    say(log, format("nearest-neighbour distance over %zu sampled centres: median %.4g, mean %.4g, 95th percentile %.4g",
                    nearest.sampled, nearest.median, nearest.mean, nearest.p95));
    cluster::NeighbourParams neighbours;
    neighbours.max_neighbours = options.max_neighbours;
    if (options.delta) {
        if (!(*options.delta > 0)) throw InputError("--delta-dist", "must be positive (or auto)");
        neighbours.delta = float(*options.delta);
    } else {
        neighbours.delta = float(cluster::auto_delta(nearest));
        say(log, format("delta (auto, 2 x median): %.4g", double(neighbours.delta)));
    }
    if (nearest.sampled > 0 && neighbours.delta < 0.5 * nearest.median)
        say(log, format("warning: delta %.4g is below half the median nearest-neighbour distance %.4g: most "
                        "Gaussians will have no neighbour and stay single",
                        double(neighbours.delta), nearest.median));
    if (nearest.sampled > 0 && neighbours.delta > 10.0 * nearest.p95)
        say(log, format("warning: delta %.4g is over 10 times the 95th-percentile nearest-neighbour distance %.4g: "
                        "each Gaussian pairs with its %zu nearest only, and clusters grow by chaining across the "
                        "scene wherever the region maps let them",
                        double(neighbours.delta), nearest.p95, neighbours.max_neighbours));
    cluster::Clustering clustering = cluster::build_clusters(positions, labels, neighbours, options.merge);
    const cluster::ClusterSummary& s = clustering.summary;
    say(log, format("clusters: %zu from %zu Gaussians (%zu singletons, largest %zu); %zu neighbour pairs, %zu merges",
                    s.clusters, s.gaussians, s.singletons, s.largest, s.pairs_considered, s.pairs_merged));
    if (s.size_percentiles.size() == 7)
        say(log, format("cluster size percentiles 0/25/50/75/90/95/100%%: %g %g %g %g %g %g %g", s.size_percentiles[0],
                        s.size_percentiles[1], s.size_percentiles[2], s.size_percentiles[3], s.size_percentiles[4],
                        s.size_percentiles[5], s.size_percentiles[6]));
    for (const auto& warning : s.warnings) say(log, "warning: " + warning);
    return clustering;
}

void log_score_table(const cluster::ClusterScores& scores, const cluster::ScoreWeights& weights, const Log& log) {
    say(log, "percentile   spatial    depth      MVR        contrib.   central.   G*");
    const auto spatial = cluster::percentiles(scores.spatial, cluster::kReportPercents);
    const auto depth = cluster::percentiles(scores.depth, cluster::kReportPercents);
    const auto mvr = cluster::percentiles(scores.mvr, cluster::kReportPercents);
    const auto contribution = cluster::percentiles(scores.contribution, cluster::kReportPercents);
    const auto centrality = cluster::percentiles(scores.centrality, cluster::kReportPercents);
    const auto total = cluster::percentiles(scores.score, cluster::kReportPercents);
    for (size_t k = 0; k < cluster::kReportPercents.size(); ++k)
        say(log, format("%9.0f%%   %-9.4f  %-9.4f  %-9.4f  %-9.4f  %-9.4f  %-9.4f", cluster::kReportPercents[k],
                        spatial[k], depth[k], mvr[k], contribution[k], centrality[k], total[k]));
    size_t central = 0, gaussians = 0;
    for (size_t c = 0; c < scores.size(); ++c) {
        gaussians += scores.members[c];
        if (scores.centrality[c] >= weights.central_threshold) central += scores.members[c];
    }
    say(log, format("central (centrality >= %.3g): %zu of %zu Gaussians (%.1f%%)", weights.central_threshold, central,
                    gaussians, gaussians ? 100.0 * double(central) / double(gaussians) : 0.0));
}

std::vector<float> cluster_gaussian_scores(Renderer& renderer, const gpu::Context& context, const GaussianCloud& input,
                                           const std::vector<Camera>& cameras, const ClusterOptions& options,
                                           const Log& log) {
    GaussianCloud cloud = input;
    const SanitizeReport report = sanitize(cloud);
    const std::vector<RegionView> regions = make_region_maps(renderer, cloud, cameras, options);
    std::vector<const RegionView*> used;
    for (size_t k : filter_views(regions, options, log)) used.push_back(&regions[k]);
    const ProjectedViews projected = project_views(renderer, context, cloud, cameras, used, options);
    const cluster::Clustering clustering = cluster_gaussians(cloud, projected.labels, options, log);
    std::vector<Camera> used_cameras;
    for (const RegionView* view : used) used_cameras.push_back(cameras[view->view]);
    const cluster::ClusterScores scores = cluster::score_clusters(cloud.positions, clustering.cluster_of, projected.labels,
                                                                  used_cameras, options.weights, projected.contribution);
    log_score_table(scores, options.weights, log);
    std::vector<float> ranks = cluster::gaussian_scores(scores, clustering.cluster_of);
    if (report.kept_indices.empty()) return ranks;
    std::vector<float> out(input.size(), -std::numeric_limits<float>::infinity());
    for (size_t i = 0; i < ranks.size(); ++i) out[report.kept_indices[i]] = ranks[i];
    return out;
}

std::vector<uint8_t> cluster_keep_mask(Renderer& renderer, const gpu::Context& context, const GaussianCloud& cloud,
                                       const std::vector<Camera>& cameras, size_t keep_count,
                                       const ClusterOptions& options, const Log& log) {
    const std::vector<float> scores = cluster_gaussian_scores(renderer, context, cloud, cameras, options, log);
    return prune::select_count(scores, keep_count, prune::keep_all(cloud.size()));
}

}  // namespace vksplat::jobs
