#include "vksplat/scene/tiled_scene.hpp"

#include <stdexcept>

namespace vksplat {

GaussianCloud tile_scene(const GaussianCloud& cloud, int nx, int ny, double spacing) {
    if (nx < 1 || ny < 1) throw std::invalid_argument("tile_scene: the grid must be at least 1 x 1");
    GaussianCloud tiled;
    tiled.sh_degree = cloud.sh_degree;
    const size_t n = cloud.size();
    tiled.resize(n * size_t(nx) * size_t(ny));
    const size_t k = size_t(cloud.sh_coefficients()) * 3;
    size_t at = 0;
    for (int j = 0; j < ny; ++j) {
        for (int i = 0; i < nx; ++i) {
            const float dx = float(spacing * (i - (nx - 1) / 2.0));
            const float dy = float(spacing * (j - (ny - 1) / 2.0));
            for (size_t g = 0; g < n; ++g, ++at) {
                tiled.positions[3 * at + 0] = cloud.positions[3 * g + 0] + dx;
                tiled.positions[3 * at + 1] = cloud.positions[3 * g + 1] + dy;
                tiled.positions[3 * at + 2] = cloud.positions[3 * g + 2];
                for (int c = 0; c < 3; ++c) tiled.log_scales[3 * at + c] = cloud.log_scales[3 * g + c];
                for (int c = 0; c < 4; ++c) tiled.rotations[4 * at + c] = cloud.rotations[4 * g + c];
                tiled.opacity_logits[at] = cloud.opacity_logits[g];
                for (size_t c = 0; c < k; ++c) tiled.sh[at * k + c] = cloud.sh[g * k + c];
            }
        }
    }
    return tiled;
}

Camera tiled_benchmark_camera() {
    Camera camera = Camera::look_at({0.0, -9.0, 7.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, 1920, 1080, 1400.0, 1400.0);
    camera.name = "tiled_5x5";
    return camera;
}

}  // namespace vksplat
