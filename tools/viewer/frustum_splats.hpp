#pragma once
// The dataset cameras' frustums drawn as splats: each edge of each frustum (four from the centre to
// the picture's corners, four around its far end) is a row of long, thin, nearly opaque Gaussians,
// so the splat renderer draws them with the scene and the viewer needs no line pipeline.
#include <vector>

#include "vksplat/camera/camera.hpp"
#include "vksplat/scene/scene.hpp"

namespace vksplat::viewer {

// Gaussians of SH degree `sh_degree` outlining each camera's frustum to `depth` in front of it,
// edges `width` thick, in a yellow that stands out against most scenes.
GaussianCloud frustum_splats(const std::vector<Camera>& cameras, double depth, double width, int sh_degree);

}  // namespace vksplat::viewer
