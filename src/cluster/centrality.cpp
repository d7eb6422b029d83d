// How much the views look at each Gaussian (see centrality.hpp).
#include "vksplat/cluster/centrality.hpp"

#include "vksplat/constants.hpp"

namespace vksplat::cluster {

std::vector<float> view_centrality(std::span<const float> positions, const std::vector<Camera>& cameras) {
    const size_t n = positions.size() / 3;
    std::vector<double> sum(n, 0.0);
    for (const Camera& camera : cameras) {
        const double half_width = 0.5 * camera.width, half_height = 0.5 * camera.height;
        for (size_t g = 0; g < n; ++g) {
            const glm::dvec3 p = camera.to_camera({positions[3 * g], positions[3 * g + 1], positions[3 * g + 2]});
            if (p.z <= constants::kNearPlane) continue;
            const double u = (camera.fx * p.x / p.z + camera.cx - half_width) / half_width;
            const double v = (camera.fy * p.y / p.z + camera.cy - half_height) / half_height;
            const double rho2 = u * u + v * v;
            if (rho2 < 1.0) sum[g] += 1.0 - rho2;
        }
    }
    std::vector<float> out(n, 0.0f);
    if (cameras.empty()) return out;
    for (size_t g = 0; g < n; ++g) out[g] = float(sum[g] / double(cameras.size()));
    return out;
}

}  // namespace vksplat::cluster
