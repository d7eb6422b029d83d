#pragma once
// A COLMAP sparse model as its files store it, before it becomes vksplat cameras. The text and the
// binary readers both produce this.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "vksplat/camera/camera.hpp"

namespace vksplat::io::detail {

struct ColmapIntrinsics {
    std::string model;  // COLMAP's model name, e.g. "PINHOLE"
    uint64_t width = 0;
    uint64_t height = 0;
    std::vector<double> params;
};

struct ColmapImage {
    std::string name;
    double qvec[4] = {1, 0, 0, 0};  // world-to-camera rotation, w x y z
    double tvec[3] = {0, 0, 0};     // world-to-camera translation
    uint32_t camera_id = 0;
};

struct ColmapModel {
    std::map<uint32_t, ColmapIntrinsics> cameras;  // by camera id
    std::vector<ColmapImage> images;
};

// A COLMAP camera as the pinhole it is without its lens distortion, and that distortion.
struct ColmapLens {
    std::string model;
    int width = 0, height = 0;
    double fx = 0, fy = 0, cx = 0, cy = 0;      // principal point in our (and COLMAP's) pixel convention
    std::vector<std::string> distortion_names;  // COLMAP's: "k", "k1", "p1", ...
    // In COLMAP's order, which for every model read here is OpenCV's (k1 k2 p1 p2 k3 k4 k5 k6)
    // with the terms the model lacks left out at the end.
    std::vector<double> distortion;
    bool distorted() const;  // any distortion term other than 0
    std::string description() const;  // the model and its distortion, e.g. "OPENCV k1=-0.12 k2=0.03 p1=0 p2=0"
};

// A COLMAP model's images as cameras, sorted by image name, with the pinhole intrinsics of their
// lens; `camera_ids[i]` is the COLMAP camera of cameras[i] and `lenses` holds those in use.
struct ColmapCameras {
    std::filesystem::path cameras_file;
    std::vector<Camera> cameras;
    std::vector<uint32_t> camera_ids;
    std::map<uint32_t, ColmapLens> lenses;
};

// The model in dir, dir/sparse/0 or dir/0 (read_colmap_cameras's folders). Throws InputError for
// a model other than SIMPLE_PINHOLE, PINHOLE, SIMPLE_RADIAL, RADIAL, OPENCV and FULL_OPENCV,
// naming it.
ColmapCameras read_colmap_lens_cameras(const std::filesystem::path& dir);

// Each throws InputError naming the file, and the line or byte where it went wrong.
// points3D readers append position (3 floats) and colour (3 floats in [0, 1]) per point.
void read_colmap_points_text(const std::filesystem::path& path, std::vector<float>& positions,
                             std::vector<float>& colors);
void read_colmap_points_binary(const std::filesystem::path& path, std::vector<float>& positions,
                               std::vector<float>& colors);
std::map<uint32_t, ColmapIntrinsics> read_colmap_cameras_text(const std::filesystem::path& path);
std::vector<ColmapImage> read_colmap_images_text(const std::filesystem::path& path);
std::map<uint32_t, ColmapIntrinsics> read_colmap_cameras_binary(const std::filesystem::path& path);
std::vector<ColmapImage> read_colmap_images_binary(const std::filesystem::path& path);

}  // namespace vksplat::io::detail
