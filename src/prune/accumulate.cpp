// Sums the blend pass's per-Gaussian statistics over many views.
#include "vksplat/prune/accumulate.hpp"

#include <numbers>
#include <string>
#include <utility>

#include "vksplat/error.hpp"
#include "vksplat/prune/fisher.hpp"
#include "vksplat/prune/scores.hpp"
#include "vksplat/train/fisher_probes.hpp"

namespace vksplat::prune {

ViewTotals accumulate(Renderer& renderer, const GaussianCloud& cloud, const std::vector<Camera>& cameras,
                      const std::vector<size_t>& views, const RenderSettings& settings, const Progress& progress,
                      bool fisher) {
    std::vector<Camera> picked;
    for (size_t view : views) {
        if (view >= cameras.size())
            throw InputError("view " + std::to_string(view),
                             "there are only " + std::to_string(cameras.size()) + " cameras");
        picked.push_back(cameras[view]);
    }
    renderer.set_scene(cloud);
    const size_t steps = picked.size() * (fisher ? 2 : 1);
    GaussianTotals sums = renderer.render_stats_totals(picked, settings, [&](size_t done, size_t) {
        if (progress) progress(done, steps);
    });

    const std::vector<float> opacity = opacities(cloud);
    ViewTotals totals(cloud.size());
    totals.views = sums.views;
    totals.blend = std::move(sums.blend_weight);
    totals.blend_max = std::move(sums.max_weight);
    totals.pixels = std::move(sums.pixels);
    totals.views_visible = std::move(sums.views_visible);
    for (size_t i = 0; i < cloud.size(); ++i)
        totals.footprint[i] = double(opacity[i]) * std::numbers::pi * double(sums.radius_squared[i]);
    if (fisher) {
        const auto matrices = train::estimate_fisher(renderer.context(), cloud, picked, settings, {},
                                                     [&](size_t done, size_t) {
                                                         if (progress) progress(picked.size() + done, steps);
                                                     });
        totals.fisher.resize(matrices.size());
        for (size_t i = 0; i < matrices.size(); ++i) totals.fisher[i] = float(fisher_log_det(matrices[i]));
    }
    return totals;
}

}  // namespace vksplat::prune
