#pragma once
// Where a set of cameras looks together. Training uses it to place a random start around what the
// cameras see; evaluation uses it to find the subject of a capture that circles one.
#include <optional>
#include <vector>

#include "vksplat/camera/camera.hpp"

namespace vksplat {

// The point nearest to all optical axes in the least-squares sense, or nothing when the axes are
// (nearly) parallel, as in a forward-facing capture.
std::optional<glm::dvec3> common_focus(const std::vector<Camera>& cameras);

}  // namespace vksplat
