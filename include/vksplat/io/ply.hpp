#pragma once
// The INRIA 3DGS .ply layout: one `vertex` element whose properties are x y z, f_dc_0..2,
// f_rest_* (channel-major: all red higher-order coefficients, then green, then blue), opacity
// (logit), scale_0..2 (log) and rot_0..3 (quaternion w, x, y, z).
#include <filesystem>
#include <string>
#include <vector>

#include "vksplat/io/write_mode.hpp"
#include "vksplat/scene/scene.hpp"

namespace vksplat::io {

// Reads binary (little- or big-endian) and ASCII PLY; properties may come in any order and be of
// any scalar type (converted to float). The SH degree follows from the number of f_rest_*
// properties (0, 9, 24, 45). Properties the cloud has no place for (normals, ...) are ignored and
// listed in one line appended to `notes`, as are skipped elements. Throws InputError naming the
// file, the element and the problem.
GaussianCloud read_ply(const std::filesystem::path& path, std::vector<std::string>* notes = nullptr);

// Writes binary little-endian float32 in the standard order
// x y z nx ny nz f_dc_0..2 f_rest_* opacity scale_0..2 rot_0..3 (normals are 0).
// Throws InputError if the cloud's arrays disagree in length or the file cannot be written.
void write_ply(const GaussianCloud& cloud, const std::filesystem::path& path,
               WriteMode mode = WriteMode::refuse_existing);

}  // namespace vksplat::io
