#pragma once
// The scene extent the reference trainer scales its position learning rate (and densification
// thresholds) by: 1.1 times the largest distance of a camera centre from the centres' mean
// (getNerfppNorm). One camera placed far off by structure from motion would set that alone, so
// cameras far from the others are left out first (robust statistics) and reported.
#include <cstddef>
#include <vector>

#include "vksplat/camera/camera.hpp"

namespace vksplat::train {

struct SceneExtent {
    double radius = 1.0;               // what TrainOptions::scene_extent takes
    std::vector<size_t> distrusted;    // cameras left out: over 10x the median distance from the median centre
};

// Throws InputError for an empty list.
SceneExtent scene_extent(const std::vector<Camera>& cameras);

}  // namespace vksplat::train
