#pragma once
// The scene extent the reference trainer scales its position learning rate (and densification
// thresholds) by: 1.1 times the largest distance of a camera centre from the centres' mean
// (getNerfppNorm). One camera placed far off by structure from motion would set that alone, so
// cameras far from the others are left out first (robust statistics) and reported.
#include <cstddef>
#include <optional>
#include <vector>

#include "vksplat/camera.hpp"

namespace vksplat::train {

struct SceneExtent {
    double radius = 1.0;               // what TrainOptions::scene_extent takes
    std::vector<size_t> distrusted;    // cameras left out: over 10x the median distance from the median centre
};

// Throws InputError for an empty list.
SceneExtent scene_extent(const std::vector<Camera>& cameras);

// Where the cameras look together: the point nearest to all optical axes in the least-squares
// sense, or nothing when the axes are (nearly) parallel, as in a forward-facing capture.
std::optional<glm::dvec3> common_focus(const std::vector<Camera>& cameras);

}  // namespace vksplat::train
