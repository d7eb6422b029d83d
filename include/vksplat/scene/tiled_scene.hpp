#pragma once
// The large benchmark scene of ../shared/data/README.md: copies of a scene on a grid.
#include "vksplat/camera/camera.hpp"
#include "vksplat/scene/scene.hpp"

namespace vksplat {

// Distance between the copies of the benchmark scene (../shared/data/README.md): lego spans about
// 2.4 units, so copies almost touch and the camera sees a dense field of them.
constexpr double kTiledBenchmarkSpacing = 2.6;

// nx * ny copies of `cloud`, copy (i, j) translated by (spacing * i, spacing * j, 0) for i, j
// centred on zero (for 5 x 5: -2..2), in row order of j then i.
GaussianCloud tile_scene(const GaussianCloud& cloud, int nx, int ny, double spacing);

// The benchmark camera for lego tiled 5x5: centre (0, -9, 7) looking at the origin, +z up,
// 1920x1080, fx = fy = 1400, principal point at the centre.
Camera tiled_benchmark_camera();

}  // namespace vksplat
