// SfM points from a COLMAP model folder, in any of the three files that hold them.
#include "vksplat/io/sfm_points.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "io/byte_order.hpp"
#include "io/colmap_model.hpp"
#include "io/ply_header.hpp"
#include "vksplat/error.hpp"

namespace vksplat::io {
namespace {

double load_scalar(const char* bytes, ply::ScalarType type) {
    switch (type) {
        case ply::ScalarType::int8: return detail::load_little_endian<int8_t>(bytes);
        case ply::ScalarType::uint8: return detail::load_little_endian<uint8_t>(bytes);
        case ply::ScalarType::int16: return detail::load_little_endian<int16_t>(bytes);
        case ply::ScalarType::uint16: return detail::load_little_endian<uint16_t>(bytes);
        case ply::ScalarType::int32: return detail::load_little_endian<int32_t>(bytes);
        case ply::ScalarType::uint32: return detail::load_little_endian<uint32_t>(bytes);
        case ply::ScalarType::float32: return detail::load_little_endian<float>(bytes);
        case ply::ScalarType::float64: return detail::load_little_endian<double>(bytes);
    }
    return 0;
}

// Keeps the points whose coordinates and colours are all finite; says how many went.
void drop_non_finite(SfmPoints& points, const std::filesystem::path& file, std::vector<std::string>* warnings) {
    const size_t n = points.size();
    size_t kept = 0;
    for (size_t i = 0; i < n; ++i) {
        bool finite = true;
        for (int k = 0; k < 3; ++k)
            finite = finite && std::isfinite(points.positions[3 * i + k]) && std::isfinite(points.colors[3 * i + k]);
        if (!finite) continue;
        for (int k = 0; k < 3; ++k) {
            points.positions[3 * kept + k] = points.positions[3 * i + k];
            points.colors[3 * kept + k] = points.colors[3 * i + k];
        }
        ++kept;
    }
    if (kept == n) return;
    points.positions.resize(3 * kept);
    points.colors.resize(3 * kept);
    if (warnings)
        warnings->push_back(file.string() + ": dropped " + std::to_string(n - kept) + " of " + std::to_string(n) +
                            " points with a non-finite coordinate or colour");
}

}  // namespace

SfmPoints read_points_ply(const std::filesystem::path& path) {
    const std::string where = path.string();
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(where, std::filesystem::exists(path) ? "cannot be opened" : "no such file");
    const ply::Header header = ply::read_header(in, where);
    if (header.format == ply::Format::binary_big_endian)
        throw InputError(where, "big-endian point clouds are not read; convert it to little-endian or ASCII");
    if (header.elements.empty() || header.elements.front().name != "vertex" || header.elements.front().has_list())
        throw InputError(where, "expected a vertex element first, without list properties");
    const ply::Element& vertex = header.elements.front();
    const char* names[6] = {"x", "y", "z", "red", "green", "blue"};
    int index[6];
    size_t offset[6];
    for (int k = 0; k < 6; ++k) {
        index[k] = -1;
        size_t at = 0;
        for (size_t p = 0; p < vertex.properties.size(); ++p) {
            if (vertex.properties[p].name == names[k]) {
                index[k] = int(p);
                offset[k] = at;
            }
            at += ply::scalar_size(vertex.properties[p].type);
        }
        if (index[k] < 0) throw InputError(where, std::string("the vertex element has no '") + names[k] + "' property");
    }
    SfmPoints points;
    points.positions.reserve(vertex.count * 3);
    points.colors.reserve(vertex.count * 3);
    const auto add = [&](const double* values) {
        for (int k = 0; k < 3; ++k) points.positions.push_back(static_cast<float>(values[k]));
        // Colours are uchar in the reference's file; any other type is taken as 0..255 too.
        for (int k = 3; k < 6; ++k) points.colors.push_back(static_cast<float>(values[k] / 255.0));
    };
    in.seekg(static_cast<std::streamoff>(header.body_offset));
    if (header.format == ply::Format::ascii) {
        std::string line;
        for (uint64_t i = 0; i < vertex.count; ++i) {
            if (!std::getline(in, line))
                throw InputError(where, "truncated: " + std::to_string(vertex.count) + " vertices declared, " +
                                            std::to_string(i) + " found");
            std::istringstream fields(line);
            std::vector<double> row(vertex.properties.size());
            for (double& v : row)
                if (!(fields >> v)) throw InputError(where, "vertex " + std::to_string(i) + ": too few values");
            double values[6];
            for (int k = 0; k < 6; ++k) values[k] = row[size_t(index[k])];
            add(values);
        }
        return points;
    }
    const size_t stride = vertex.fixed_stride();
    std::vector<char> bytes(stride);
    for (uint64_t i = 0; i < vertex.count; ++i) {
        if (!in.read(bytes.data(), static_cast<std::streamsize>(stride)))
            throw InputError(where, "truncated: " + std::to_string(vertex.count) + " vertices declared, " +
                                        std::to_string(i) + " found");
        double values[6];
        for (int k = 0; k < 6; ++k) values[k] = load_scalar(bytes.data() + offset[k], vertex.properties[size_t(index[k])].type);
        add(values);
    }
    return points;
}

SfmPoints read_sfm_points(const std::filesystem::path& model_dir, std::vector<std::string>* warnings) {
    SfmPoints points;
    std::filesystem::path file;
    if (std::filesystem::exists(file = model_dir / "points3D.bin"))
        detail::read_colmap_points_binary(file, points.positions, points.colors);
    else if (std::filesystem::exists(file = model_dir / "points3D.txt"))
        detail::read_colmap_points_text(file, points.positions, points.colors);
    else if (std::filesystem::exists(file = model_dir / "points3D.ply"))
        points = read_points_ply(file);
    else
        throw InputError(model_dir.string(), "holds no points3D.bin, points3D.txt or points3D.ply");
    drop_non_finite(points, file, warnings);
    return points;
}

}  // namespace vksplat::io
