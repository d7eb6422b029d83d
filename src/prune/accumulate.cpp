// Sums the blend pass's per-Gaussian statistics over many views.
#include "vksplat/prune/accumulate.hpp"

#include <algorithm>
#include <numbers>
#include <optional>
#include <string>

#include "vksplat/error.hpp"
#include "vksplat/prune/fisher.hpp"
#include "vksplat/prune/scores.hpp"

namespace vksplat::prune {
namespace {

void add_view(ViewTotals& totals, const GaussianStats& stats, const std::vector<float>& opacity) {
    for (size_t i = 0; i < totals.size(); ++i) {
        totals.blend[i] += stats.blend_weight[i];
        totals.blend_max[i] = std::max(totals.blend_max[i], stats.max_weight[i]);
        totals.pixels[i] += stats.pixels[i];
        if (!stats.visible[i]) continue;
        const double radius = stats.radius[i];
        totals.footprint[i] += double(opacity[i]) * std::numbers::pi * radius * radius;
        ++totals.views_visible[i];
    }
}

}  // namespace

ViewTotals accumulate(Renderer& renderer, const GaussianCloud& cloud, const std::vector<Camera>& cameras,
                      const std::vector<size_t>& views, const RenderSettings& settings, const Progress& progress,
                      bool fisher) {
    for (size_t view : views)
        if (view >= cameras.size())
            throw InputError("view " + std::to_string(view),
                             "there are only " + std::to_string(cameras.size()) + " cameras");
    renderer.set_scene(cloud);
    const std::vector<float> opacity = opacities(cloud);

    ViewTotals totals(cloud.size());
    std::optional<FisherInformation> information;
    if (fisher) information.emplace(cloud, settings);
    for (size_t done = 0; done < views.size(); ++done) {
        add_view(totals, renderer.render_stats(cameras[views[done]], settings), opacity);
        if (information) information->add_view(cameras[views[done]]);
        ++totals.views;
        if (progress) progress(done + 1, views.size());
    }
    if (information) totals.fisher = information->log_dets();
    return totals;
}

}  // namespace vksplat::prune
