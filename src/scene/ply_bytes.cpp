// The size of the INRIA .ply a cloud saves to: the figure a user compares when pruning a scene.
#include <string>

#include "vksplat/scene/scene.hpp"

namespace vksplat {
namespace {

// Bytes of "property float <name>\n".
size_t property_line(const std::string& name) { return std::string("property float \n").size() + name.size(); }

// The header INRIA's trainer writes (through plyfile) and io::write_ply reproduces: format line,
// one vertex element, float properties x y z nx ny nz f_dc_0..2 f_rest_* opacity scale_0..2 rot_0..3.
size_t header_bytes(size_t count, int rest) {
    size_t bytes = std::string("ply\nformat binary_little_endian 1.0\nelement vertex \n").size() +
                   std::to_string(count).size() + std::string("end_header\n").size();
    for (const char* name : {"x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2", "opacity", "scale_0",
                             "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"})
        bytes += property_line(name);
    for (int i = 0; i < rest; ++i) bytes += property_line("f_rest_" + std::to_string(i));
    return bytes;
}

}  // namespace

size_t GaussianCloud::ply_bytes() const {
    const int rest = (sh_coefficients() - 1) * 3;
    // Per Gaussian: position, normals, DC colour, f_rest, opacity, scale, rotation; all float32.
    const size_t row_floats = 3 + 3 + 3 + static_cast<size_t>(rest) + 1 + 3 + 4;
    return header_bytes(size(), rest) + size() * row_floats * sizeof(float);
}

}  // namespace vksplat
