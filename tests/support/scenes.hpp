#pragma once
// Small scenes the tests generate themselves, each aimed at an edge case of the renderer.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "vksplat/camera/camera.hpp"
#include "vksplat/render_types.hpp"
#include "vksplat/scene/scene.hpp"

namespace vksplat::test {

// A camera at the origin looking down +z (identity world->camera), principal point centred.
Camera forward_camera(int width, int height, double focal);

// `count` 64x48 cameras on a circle of `radius` around `target`, looking at it, their heights
// wavering by radius / 8 so that the ring is not flat.
std::vector<Camera> camera_ring(int count, glm::dvec3 target, double radius);

// One Gaussian in activated terms, so a test states what it renders rather than logits and SH.
struct Splat {
    glm::dvec3 position{0.0};
    glm::dvec3 scale{0.1};                    // standard deviations
    glm::dvec4 rotation{1.0, 0.0, 0.0, 0.0};  // quaternion w, x, y, z
    double opacity = 0.5;
    glm::dvec3 color{1.0, 0.5, 0.25};         // the colour it renders as (the DC term)
};

// Appends a Gaussian to a cloud of any SH degree; higher bands are zero.
void add_splat(GaussianCloud& cloud, const Splat& splat);

// The view-space position at depth z whose splat centre lands on pixel coordinates (u, v); for
// forward_camera it is also the world position.
glm::dvec3 at_pixel(const Camera& camera, double u, double v, double z);

// n Gaussians in front of forward_camera: positions in a box at depth [z_near, z_far],
// random anisotropic scales within [scale_min, scale_max], random rotations and opacities,
// random SH of the given degree. Deterministic for a seed.
GaussianCloud random_scene(uint32_t seed, size_t n, int sh_degree, float z_near = 2.0f, float z_far = 8.0f,
                           float scale_min = 0.01f, float scale_max = 0.3f, float half_width = 2.5f);

// What the Fisher tests differentiate: two overlapping views and, over a coloured background
// (`settings`), overlapping splats of SH degree 1 (the colour moves with the view direction), one
// opaque enough that its alpha is clamped at 0.99 near its centre and one centred beyond the
// Jacobian's clamp at the right but large enough to reach into the picture.
struct FisherScene {
    std::vector<Camera> cameras;
    GaussianCloud cloud;
    RenderSettings settings;
};
FisherScene fisher_scene();

// Five 48x40 views ("view_0" .. "view_4") on a row in front of the origin, all looking at
// (0, 0, 5): the small multi-view set of the pruning and sweep tests.
std::vector<Camera> row_of_five_views();

}  // namespace vksplat::test
