#pragma once
// Lens distortion taken out of COLMAP photos at load, with OpenCV, as the reference's convert.py
// has COLMAP's image_undistorter do before training: the cameras become PINHOLE and each photo is
// remapped to them when it is read, so that the trainer, renderer and evaluator see pinholes only.
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "io/colmap_model.hpp"
#include "vksplat/io/dataset.hpp"

namespace vksplat::io {

struct PhotoUndistortion::Lens {
    int width = 0, height = 0;  // the photos' size, the same before and after
    cv::Mat map1, map2;         // cv::remap's fixed-point maps: undistorted pixel -> position in the photo
};

namespace detail {

// Gives each camera of `model` whose lens has distortion the pinhole intrinsics of its undistorted
// photos, and returns what undistorts them; appends one notice per such COLMAP camera saying so.
PhotoUndistortion undistort_cameras(ColmapCameras& model, std::vector<std::string>& notices);

}  // namespace detail
}  // namespace vksplat::io
