#pragma once
// How frame time grows with the picture and with the scene: one view benchmarked at several
// resolutions, and a scene thinned or tiled to several sizes. What `vksplat bench --scaling` does.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "vksplat/camera/camera.hpp"
#include "vksplat/bench/benchmark.hpp"
#include "vksplat/render/renderer.hpp"
#include "vksplat/scene/scene.hpp"

namespace vksplat::bench {

struct ScalingPoint {
    std::string label;       // "1920x1080", "5x5 tiles", "10% subset"
    double x = 0;            // pixels, or Gaussians
    uint64_t gaussians = 0;
    ViewBenchmark bench;
};

// `camera` at each size (with_resolution: focal length per unit of width kept).
std::vector<ScalingPoint> benchmark_resolutions(Renderer& renderer, const Camera& camera,
                                                const std::vector<std::array<int, 2>>& sizes,
                                                const BenchmarkOptions& options);

// A scene of about `count` Gaussians made from `base`: every k-th Gaussian when count is below
// its size, else base tiled n x n (n = round(sqrt(count / size)), at least 1) `spacing` apart.
GaussianCloud scene_of_size(const GaussianCloud& base, uint64_t count, double spacing, std::string* label = nullptr);

// For each count, uploads scene_of_size(base, count) and benchmarks `camera` on it.
std::vector<ScalingPoint> benchmark_scene_sizes(Renderer& renderer, const GaussianCloud& base,
                                                const std::vector<uint64_t>& counts, double spacing,
                                                const Camera& camera, const BenchmarkOptions& options,
                                                const SceneStorage& storage = {});

}  // namespace vksplat::bench
