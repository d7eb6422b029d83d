#pragma once
// Small scenes the tests generate themselves, each aimed at an edge case of the renderer.
#include <cstdint>
#include <vector>

#include "vksplat/camera.hpp"
#include "vksplat/scene.hpp"

namespace vksplat::test {

// A camera at the origin looking down +z (identity world->camera), principal point centred.
Camera forward_camera(int width, int height, double focal);

// Appends one Gaussian. scale is the standard deviation (not its log), opacity in (0, 1),
// rgb the colour it should show (written as the DC term); higher SH bands are left zero.
void add_gaussian(GaussianCloud& cloud, const float position[3], const float scale[3], const float quaternion[4],
                  float opacity, const float rgb[3]);

// n Gaussians in front of forward_camera: positions in a box at depth [z_near, z_far],
// random anisotropic scales within [scale_min, scale_max], random rotations and opacities,
// random SH of the given degree. Deterministic for a seed.
GaussianCloud random_scene(uint32_t seed, size_t n, int sh_degree, float z_near = 2.0f, float z_far = 8.0f,
                           float scale_min = 0.01f, float scale_max = 0.3f, float half_width = 2.5f);

}  // namespace vksplat::test
