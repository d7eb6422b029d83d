// vksplat_prune: scores over the caller's views, the lossless pass, then drop by ratio; the same
// steps, from the prune module, that `vksplat prune --ratio` takes before it measures and writes.
#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include "capi/call.hpp"
#include "capi/conversions.hpp"
#include "capi/handles.hpp"
#include "vksplat/prune/accumulate.hpp"
#include "vksplat/prune/scores.hpp"
#include "vksplat/prune/selection.hpp"

using vksplat::capi::guarded;
using vksplat::capi::out_pointer;
using vksplat::capi::require;

namespace {

vksplat::prune::ScoreMethod to_method(vksplat_score_method method) {
    using vksplat::prune::ScoreMethod;
    switch (method) {
        case VKSPLAT_SCORE_OPACITY: return ScoreMethod::opacity;
        case VKSPLAT_SCORE_FOOTPRINT: return ScoreMethod::footprint;
        case VKSPLAT_SCORE_BLEND: return ScoreMethod::blend;
        case VKSPLAT_SCORE_BLEND_MAX: return ScoreMethod::blend_max;
        case VKSPLAT_SCORE_VOLUME_BLEND: return ScoreMethod::volume_blend;
        case VKSPLAT_SCORE_RANDOM: return ScoreMethod::random;
        case VKSPLAT_SCORE_FISHER: return ScoreMethod::fisher;
        case VKSPLAT_SCORE_BLEND_MIX: return ScoreMethod::blend_mix;
    }
    throw std::invalid_argument("options->method " + std::to_string(int(method)) + " is no vksplat_score_method");
}

}  // namespace

extern "C" {

vksplat_status vksplat_prune(vksplat_renderer* renderer, const vksplat_scene* scene,
                             const vksplat_prune_options* options, vksplat_scene** pruned, vksplat_error* error) {
    return guarded(__func__, error, [&] {
        vksplat_scene*& out = out_pointer(pruned, "pruned");
        const vksplat_prune_options& asked = require(options, "options");
        const vksplat::prune::ScoreMethod method = to_method(asked.method);
        vksplat::GaussianCloud cloud = require(scene, "scene").cloud;
        vksplat::sanitize(cloud);  // scores expect finite scales; the renderer would sanitise it anyway

        vksplat::prune::ViewTotals totals;
        vksplat::prune::KeepMask candidates;
        if (asked.view_count > 0) {
            require(asked.views, "options->views");
            vksplat::Renderer& source = require(renderer, "renderer").renderer;
            std::vector<vksplat::Camera> cameras;
            for (size_t v = 0; v < asked.view_count; ++v)
                cameras.push_back(vksplat::capi::to_camera(asked.views[v], "views[" + std::to_string(v) + "]"));
            std::vector<size_t> views(cameras.size());
            std::iota(views.begin(), views.end(), size_t{0});
            totals = vksplat::prune::accumulate(source, cloud, cameras, views, vksplat::capi::to_settings(asked.settings),
                                                {}, vksplat::prune::needs_fisher(method));
            candidates = vksplat::prune::lossless_mask(totals);
        } else if (vksplat::prune::uses_views(method)) {
            throw std::invalid_argument("options->method " + std::string(vksplat::prune::to_string(method)) +
                                        " scores over views: give at least one in options->views");
        } else {
            candidates = vksplat::prune::keep_all(cloud.size());
        }
        const std::vector<float> scores = vksplat::prune::score(cloud, totals, method, asked.seed);
        const vksplat::prune::KeepMask keep = vksplat::prune::select_ratio(scores, asked.ratio, candidates);
        out = new vksplat_scene{cloud.subset(keep)};
    });
}

}  // extern "C"
