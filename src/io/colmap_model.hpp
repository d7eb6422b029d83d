#pragma once
// A COLMAP sparse model as its files store it, before it becomes vksplat cameras. The text and the
// binary readers both produce this.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

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
