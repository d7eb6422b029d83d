#include "jobs/scene_importance.hpp"

#include "vksplat/prune/accumulate.hpp"
#include "vksplat/prune/selection.hpp"

namespace vksplat::jobs {

train::Importance importance_over(const gpu::Context& context, std::vector<Camera> cameras, std::vector<size_t> views,
                                  const RenderSettings& settings, prune::ScoreMethod method, uint64_t seed,
                                  bool sampled) {
    return [&context, cameras = std::move(cameras), views = std::move(views), settings, method, seed,
            sampled](const GaussianCloud& cloud) {
        Renderer renderer(context);
        const prune::ViewTotals totals =
            prune::accumulate(renderer, cloud, cameras, views, settings, {}, prune::needs_fisher(method));
        std::vector<float> scores = prune::score(cloud, totals, method, seed);
        if (!sampled) return scores;
        return prune::sampling_keys(prune::sampling_weights(scores, method), seed ^ (uint64_t(cloud.size()) << 20));
    };
}

}  // namespace vksplat::jobs
