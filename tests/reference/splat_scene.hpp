#pragma once
// Builds small scenes for the reference rasterizer's tests from activated values (scale,
// opacity, colour), so each test states what it renders rather than logits and SH coefficients.
#include <cmath>

#include <glm/glm.hpp>

#include "vksplat/camera.hpp"
#include "vksplat/reference/sh.hpp"
#include "vksplat/scene.hpp"

namespace vksplat::test {

struct Splat {
    glm::dvec3 position{0.0};
    glm::dvec3 scale{0.1};                   // standard deviations
    glm::dvec4 rotation{1.0, 0.0, 0.0, 0.0};  // quaternion w, x, y, z
    double opacity = 0.5;
    glm::dvec3 color{1.0, 0.5, 0.25};        // the colour it renders as (SH degree 0)
};

// Appends a Gaussian to a cloud of any SH degree; higher bands are zero.
inline void add_splat(GaussianCloud& cloud, const Splat& s) {
    const size_t i = cloud.size();
    cloud.resize(i + 1);
    for (int k = 0; k < 3; ++k) {
        cloud.positions[i * 3 + k] = static_cast<float>(s.position[k]);
        cloud.log_scales[i * 3 + k] = static_cast<float>(std::log(s.scale[k]));
        // colour = C0 * dc + 0.5
        cloud.sh[i * cloud.sh_coefficients() * 3 + k] =
            static_cast<float>((s.color[k] - 0.5) / reference::kShC0);
    }
    for (int k = 0; k < 4; ++k) cloud.rotations[i * 4 + k] = static_cast<float>(s.rotation[k]);
    cloud.opacity_logits[i] = static_cast<float>(std::log(s.opacity / (1.0 - s.opacity)));
}

// At the origin looking along +z (identity rotation), principal point at the image centre.
inline Camera identity_camera(int width, int height, double focal) {
    Camera camera;
    camera.name = "identity";
    camera.width = width;
    camera.height = height;
    camera.fx = camera.fy = focal;
    camera.cx = width / 2.0;
    camera.cy = height / 2.0;
    return camera;
}

// The view-space position at depth z whose splat centre lands on pixel coordinates (u, v); for
// identity_camera it is also the world position.
inline glm::dvec3 at_pixel(const Camera& camera, double u, double v, double z) {
    return {(u + 0.5 - camera.cx) * z / camera.fx, (v + 0.5 - camera.cy) * z / camera.fy, z};
}

}  // namespace vksplat::test
