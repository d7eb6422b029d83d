// The cameras' common focus (see camera_focus.hpp).
#include "vksplat/camera/camera_focus.hpp"

#include <algorithm>
#include <cmath>

namespace vksplat {

std::optional<glm::dvec3> common_focus(const std::vector<Camera>& cameras) {
    // Minimises sum_i |(I - d_i d_i^T)(p - c_i)|^2 over p, d_i the unit viewing direction (the
    // camera's z axis in the world) and c_i the centre: a 3x3 linear system.
    glm::dmat3 a(0.0);
    glm::dvec3 b(0.0);
    for (const Camera& camera : cameras) {
        const glm::dvec3 d = glm::normalize(glm::transpose(camera.rotation)[2]);
        const glm::dmat3 projector = glm::dmat3(1.0) - glm::outerProduct(d, d);
        a += projector;
        b += projector * camera.centre();
    }
    // Parallel axes leave the system (near) singular: no common focus.
    const double scale = std::max(1.0, double(cameras.size()));
    if (cameras.size() < 2 || std::abs(glm::determinant(a / scale)) < 1e-6) return std::nullopt;
    return glm::inverse(a) * b;
}

}  // namespace vksplat
