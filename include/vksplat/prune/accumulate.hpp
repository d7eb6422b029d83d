#pragma once
// What each Gaussian contributed over a set of views: the per-view statistics of the blend pass
// (RenderSettings::gather_stats) summed per Gaussian. Every view-based score is computed from these
// totals, so they are gathered once (and can be saved, see score_files.hpp).
//
//   prune::ViewTotals totals = prune::accumulate(renderer, cloud, cameras, train_views, settings);
//   std::vector<float> scores = prune::score(cloud, totals, prune::ScoreMethod::blend);
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "vksplat/camera/camera.hpp"
#include "vksplat/render/renderer.hpp"

namespace vksplat::prune {

// Per Gaussian, indexed like the cloud that was accumulated.
struct ViewTotals {
    std::vector<double> blend;             // sum over views and pixels of alpha * T
    std::vector<float> blend_max;          // max over views and pixels of alpha * T
    std::vector<uint64_t> pixels;          // pixels where alpha reached 1/255, summed over views
    std::vector<double> footprint;         // sum over views of opacity * pi * radius^2 (visible views)
    std::vector<uint32_t> views_visible;   // views in which it survived culling
    // log det of PUP 3D-GS's Fisher information summed over the views (fisher.hpp), estimated by
    // random-sign probes through the backward pass (train/fisher_probes.hpp); empty unless
    // accumulate() was asked for it.
    std::vector<float> fisher;
    size_t views = 0;                      // how many views were summed

    ViewTotals() = default;
    explicit ViewTotals(size_t n)
        : blend(n, 0.0), blend_max(n, 0.0f), pixels(n, 0), footprint(n, 0.0), views_visible(n, 0) {}
    size_t size() const { return blend.size(); }
};

using Progress = std::function<void(size_t done, size_t total)>;

// Uploads `cloud` (replacing the renderer's scene, so that the statistics are indexed like it),
// renders the statistics of each of `views` (indices into `cameras`) and sums them
// (Renderer::render_stats_totals, which sums them on the device where it can); the footprint is
// opacity * pi * the summed squared radii. `settings` gives the background and SH degree. With
// `fisher` it also estimates the Fisher information of each view (ViewTotals::fisher; the cloud must
// be sanitised), train::estimate_fisher's probes after the renders: `progress` then counts to
// twice the views.
// Throws InputError for a view index out of range.
ViewTotals accumulate(Renderer& renderer, const GaussianCloud& cloud, const std::vector<Camera>& cameras,
                      const std::vector<size_t>& views, const RenderSettings& settings,
                      const Progress& progress = {}, bool fisher = false);

}  // namespace vksplat::prune
