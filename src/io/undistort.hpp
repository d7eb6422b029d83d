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

// The remap's maps are made for each photo rather than kept: at 6 bytes a pixel they weigh 98 MB
// for a 16-megapixel camera, and COLMAP gives every image a camera of its own unless told
// otherwise, while making them takes about half as long as the remap itself (58 vs 107 ms).
struct PhotoUndistortion::Lens {
    int width = 0, height = 0;    // the photos' size, the same before and after
    cv::Matx33d distorted;        // OpenCV's pixel convention (pixel centres on whole numbers)
    std::vector<double> terms;    // OpenCV's distortion coefficients
    cv::Matx33d undistorted;      // the pinhole the photos are remapped to
};

namespace detail {

// Gives each camera of `model` whose lens has distortion the pinhole intrinsics of its undistorted
// photos, and returns what undistorts them; appends one notice per such COLMAP camera saying so.
PhotoUndistortion undistort_cameras(ColmapCameras& model, std::vector<std::string>& notices);

}  // namespace detail
}  // namespace vksplat::io
