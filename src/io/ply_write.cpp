// Writes the standard INRIA layout, the one every 3DGS viewer and trainer reads.
#include <algorithm>
#include <bit>

#include "vksplat/error.hpp"
#include "vksplat/io/ply.hpp"

namespace vksplat::io {
namespace {

// The body is written as the host's floats.
static_assert(std::endian::native == std::endian::little, "write_ply assumes a little-endian host");

void check_cloud(const GaussianCloud& cloud, const std::string& where) {
    try {
        cloud.check_consistent();
    } catch (const std::exception& error) {
        throw InputError(where, std::string("cannot write an inconsistent cloud: ") + error.what());
    }
}

std::string header_for(const GaussianCloud& cloud) {
    std::string header = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(cloud.size()) + "\n";
    for (const char* name : {"x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2"})
        header += std::string("property float ") + name + "\n";
    const int rest = (cloud.sh_coefficients() - 1) * 3;
    for (int i = 0; i < rest; ++i) header += "property float f_rest_" + std::to_string(i) + "\n";
    for (const char* name : {"opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"})
        header += std::string("property float ") + name + "\n";
    return header + "end_header\n";
}

}  // namespace

void write_ply(const GaussianCloud& cloud, const std::filesystem::path& path, WriteMode mode) {
    check_cloud(cloud, path.string());
    const size_t coefficients = static_cast<size_t>(cloud.sh_coefficients());
    const size_t row_floats = 3 + 3 + 3 + (coefficients - 1) * 3 + 1 + 3 + 4;

    write_file_atomically(path, mode, [&](std::ostream& out) {
        out << header_for(cloud);
        // Rows are assembled in batches: one write per batch, without a copy of the whole cloud.
        constexpr size_t kBatch = 16384;
        std::vector<float> rows;
        rows.reserve(kBatch * row_floats);
        for (size_t first = 0; first < cloud.size(); first += kBatch) {
            rows.clear();
            for (size_t i = first; i < std::min(first + kBatch, cloud.size()); ++i) {
                const float* sh = cloud.sh.data() + i * coefficients * 3;
                rows.insert(rows.end(), cloud.positions.begin() + i * 3, cloud.positions.begin() + i * 3 + 3);
                rows.insert(rows.end(), {0.0f, 0.0f, 0.0f});  // normals
                rows.insert(rows.end(), sh, sh + 3);          // DC
                // f_rest is channel-major: every red coefficient, then green, then blue.
                for (size_t channel = 0; channel < 3; ++channel)
                    for (size_t k = 1; k < coefficients; ++k) rows.push_back(sh[k * 3 + channel]);
                rows.push_back(cloud.opacity_logits[i]);
                rows.insert(rows.end(), cloud.log_scales.begin() + i * 3, cloud.log_scales.begin() + i * 3 + 3);
                rows.insert(rows.end(), cloud.rotations.begin() + i * 4, cloud.rotations.begin() + i * 4 + 4);
            }
            out.write(reinterpret_cast<const char*>(rows.data()),
                      static_cast<std::streamsize>(rows.size() * sizeof(float)));
        }
    });
}

}  // namespace vksplat::io
