#pragma once
// The reference rasterizer: THE ORACLE for the GPU renderer's tests.
//
// Plain C++ in double precision, written to be obviously the same math as the forward pass of the
// CUDA reference (graphdeco-inria diff-gaussian-rasterization: preprocessCUDA, duplicateWithKeys +
// the (tile, depth) sort, renderCUDA), with the constants of vksplat/constants.hpp. It is kept
// simple rather than fast (single thread, no SIMD): use it on small scenes and small images.
// Unlike the CUDA code it takes any image size and an off-centre principal point.
#include <array>
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "vksplat/camera/camera.hpp"
#include "vksplat/render_types.hpp"
#include "vksplat/scene/scene.hpp"

namespace vksplat::reference {

// One Gaussian after the reference's preprocess step. When `visible` is false the Gaussian is
// culled (at or behind the near plane, singular 2D covariance, or an empty tile rectangle): the
// fields computed before the failed test keep their values, the rest stay at their defaults.
struct ProjectedGaussian {
    bool visible = false;
    double depth = 0.0;           // view-space z
    glm::dvec2 mean{0.0};         // pixel coordinates: pixel (i, j) is evaluated at exactly (i, j)
    glm::dvec3 cov2d{0.0};        // 2D covariance (a, b, c) = [[a, b], [b, c]], low-pass filter included
    // Inverse 2D covariance (a', b', c'): alpha = opacity * exp(-0.5 (a' dx^2 + c' dy^2) - b' dx dy).
    glm::dvec3 conic{0.0};
    double opacity = 0.0;         // sigmoid of the logit
    std::array<double, 3> color{};  // SH + 0.5, clamped at 0
    int radius = 0;               // pixels: ceil(3 sigma of the larger eigenvalue)
    // Tile rectangle, half-open: tiles [rect_min.x, rect_max.x) x [rect_min.y, rect_max.y).
    glm::ivec2 rect_min{0};
    glm::ivec2 rect_max{0};
};

// The preprocess step for Gaussian `index`: activations, near-plane cull, EWA projection of the
// covariance, conic, radius, tile rectangle and colour. sh_degree is the degree to evaluate,
// capped to 0..cloud.sh_degree.
ProjectedGaussian project(const GaussianCloud& cloud, size_t index, const Camera& camera, int sh_degree);

// Renders the cloud: preprocess, per-tile lists in (depth, index) order, front-to-back blending.
// Uses SH degree min(cloud.sh_degree, settings.max_sh_degree). Throws if the camera fails
// Camera::validate() or the cloud's arrays are inconsistent.
RenderOutput render(const GaussianCloud& cloud, const Camera& camera, const RenderSettings& settings);

// The same picture's colour (background included) without rounding to float: 3 values per
// pixel, row-major. What finite differences of the renderer are taken on.
std::vector<double> render_rgb(const GaussianCloud& cloud, const Camera& camera, const RenderSettings& settings);

}  // namespace vksplat::reference
