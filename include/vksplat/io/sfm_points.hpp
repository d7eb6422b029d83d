#pragma once
// The points structure from motion found, which training starts its Gaussians from.
#include <filesystem>
#include <string>
#include <vector>

namespace vksplat::io {

struct SfmPoints {
    std::vector<float> positions;  // x, y, z per point
    std::vector<float> colors;     // r, g, b in [0, 1] per point
    size_t size() const { return positions.size() / 3; }
};

// The points of a COLMAP model folder (sparse/0): points3D.bin, points3D.txt or points3D.ply
// (what the reference trainer writes beside them), the first found in that order. Throws
// InputError naming the file for a malformed or truncated one, or the folder when it has none.
// Points with a non-finite coordinate or colour are dropped, and `warnings` told how many: in
// the neighbour search that sizes the starting Gaussians (train/initialize.hpp) they would throw
// off the scales of the others.
SfmPoints read_sfm_points(const std::filesystem::path& model_dir, std::vector<std::string>* warnings = nullptr);

// A point-cloud PLY: a vertex element with x, y, z and red, green, blue (uchar), as binary
// little-endian or ASCII with no list properties.
SfmPoints read_points_ply(const std::filesystem::path& path);

}  // namespace vksplat::io
