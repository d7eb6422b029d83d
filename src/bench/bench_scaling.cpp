#include "vksplat/bench/bench_scaling.hpp"

#include <algorithm>
#include <cmath>

#include "vksplat/error.hpp"
#include "vksplat/scene/tiled_scene.hpp"

namespace vksplat::bench {

std::vector<ScalingPoint> benchmark_resolutions(Renderer& renderer, const Camera& camera,
                                                const std::vector<std::array<int, 2>>& sizes,
                                                const BenchmarkOptions& options) {
    std::vector<ScalingPoint> points;
    for (const auto& [width, height] : sizes) {
        const std::vector<Camera> resized{with_resolution(camera, width, height)};
        ScalingPoint point;
        point.label = std::to_string(width) + "x" + std::to_string(height);
        point.x = double(width) * height;
        point.gaussians = renderer.scene_size();
        point.bench = benchmark_views(renderer, resized, {0}, options, "").views.front();
        points.push_back(std::move(point));
    }
    return points;
}

GaussianCloud scene_of_size(const GaussianCloud& base, uint64_t count, double spacing, std::string* label) {
    if (base.empty() || count == 0) throw InputError("scene size", "needs a scene and a positive count");
    if (count < base.size()) {
        // Every k-th Gaussian (k fractional, so the count is met): a thinned copy of the whole
        // scene rather than a corner of it, so the picture covers the same pixels.
        std::vector<uint8_t> keep(base.size(), 0);
        const double step = double(base.size()) / double(count);
        for (uint64_t i = 0; i < count; ++i) keep[std::min(size_t(double(i) * step), base.size() - 1)] = 1;
        if (label) *label = "1/" + std::to_string(int(std::lround(step))) + " subset";
        return base.subset(keep);
    }
    const int n = std::max(1, int(std::lround(std::sqrt(double(count) / double(base.size())))));
    if (label) *label = std::to_string(n) + "x" + std::to_string(n) + " tiles";
    return n == 1 ? base : tile_scene(base, n, n, spacing);
}

std::vector<ScalingPoint> benchmark_scene_sizes(Renderer& renderer, const GaussianCloud& base,
                                                const std::vector<uint64_t>& counts, double spacing,
                                                const Camera& camera, const BenchmarkOptions& options,
                                                const SceneStorage& storage) {
    std::vector<ScalingPoint> points;
    for (uint64_t count : counts) {
        ScalingPoint point;
        const GaussianCloud scene = scene_of_size(base, count, spacing, &point.label);
        renderer.set_scene(scene, storage);
        point.gaussians = renderer.scene_size();
        point.x = double(point.gaussians);
        point.bench = benchmark_views(renderer, {camera}, {0}, options, "").views.front();
        points.push_back(std::move(point));
    }
    return points;
}

}  // namespace vksplat::bench
