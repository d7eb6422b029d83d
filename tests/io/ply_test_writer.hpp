#pragma once
// Writes PLY files the way other tools do (any format, property order and type), independently of
// the writer under test, so that the reader is checked against files it did not produce.
#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "vksplat/scene/scene.hpp"

namespace vksplat::io::test {

enum class PlyFormat { ascii, little_endian, big_endian };

struct HandProperty {
    std::string type;  // "float", "double", "uchar", "short", "int", ...
    std::string name;
};

template <typename T>
std::string raw_bytes(T value, bool big_endian) {
    std::string bytes(sizeof(T), '\0');
    std::memcpy(bytes.data(), &value, sizeof(T));
    if (big_endian == (std::endian::native == std::endian::little)) std::reverse(bytes.begin(), bytes.end());
    return bytes;
}

inline std::string encode_value(double value, const std::string& type, bool big_endian) {
    if (type == "float") return raw_bytes(static_cast<float>(value), big_endian);
    if (type == "double") return raw_bytes(value, big_endian);
    if (type == "uchar") return raw_bytes(static_cast<uint8_t>(value), big_endian);
    if (type == "char") return raw_bytes(static_cast<int8_t>(value), big_endian);
    if (type == "short") return raw_bytes(static_cast<int16_t>(value), big_endian);
    if (type == "ushort") return raw_bytes(static_cast<uint16_t>(value), big_endian);
    if (type == "int") return raw_bytes(static_cast<int32_t>(value), big_endian);
    if (type == "uint") return raw_bytes(static_cast<uint32_t>(value), big_endian);
    throw std::invalid_argument("encode_value: unknown type " + type);
}

inline std::string format_line(PlyFormat format) {
    switch (format) {
        case PlyFormat::ascii:
            return "format ascii 1.0\n";
        case PlyFormat::little_endian:
            return "format binary_little_endian 1.0\n";
        case PlyFormat::big_endian:
            return "format binary_big_endian 1.0\n";
    }
    return "";
}

inline std::string property_lines(const std::vector<HandProperty>& properties) {
    std::string text;
    for (const auto& property : properties) text += "property " + property.type + " " + property.name + "\n";
    return text;
}

// The body of the rows (one per vertex, values in property order).
inline std::string body_of(PlyFormat format, const std::vector<HandProperty>& properties,
                           const std::vector<std::vector<double>>& rows) {
    std::string body;
    for (const auto& row : rows) {
        for (size_t p = 0; p < properties.size(); ++p) {
            if (format == PlyFormat::ascii) {
                char text[32];
                std::snprintf(text, sizeof text, "%.9g", row[p]);
                if (p) body += ' ';
                body += text;
            } else {
                body += encode_value(row[p], properties[p].type, format == PlyFormat::big_endian);
            }
        }
        if (format == PlyFormat::ascii) body += "\n";
    }
    return body;
}

// A whole file with one vertex element.
inline std::string hand_made_ply(PlyFormat format, const std::vector<HandProperty>& properties,
                                 const std::vector<std::vector<double>>& rows) {
    return "ply\n" + format_line(format) + "comment made by hand\nelement vertex " + std::to_string(rows.size()) +
           "\n" + property_lines(properties) + "end_header\n" + body_of(format, properties, rows);
}

// The INRIA property names for a degree, in the standard order without normals.
inline std::vector<std::string> inria_names(int sh_degree) {
    std::vector<std::string> names = {"x", "y", "z", "f_dc_0", "f_dc_1", "f_dc_2"};
    for (int i = 0; i < (sh_coefficients_for_degree(sh_degree) - 1) * 3; ++i)
        names.push_back("f_rest_" + std::to_string(i));
    for (const char* name : {"opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"})
        names.push_back(name);
    return names;
}

// Gaussian i's INRIA property values by name: f_rest is channel-major.
inline std::map<std::string, double> inria_values(const GaussianCloud& cloud, size_t i) {
    std::map<std::string, double> values;
    const size_t k = static_cast<size_t>(cloud.sh_coefficients());
    for (size_t a = 0; a < 3; ++a) {
        values[std::string(1, "xyz"[a])] = cloud.positions[i * 3 + a];
        values["scale_" + std::to_string(a)] = cloud.log_scales[i * 3 + a];
        values["f_dc_" + std::to_string(a)] = cloud.sh[i * k * 3 + a];
        for (size_t c = 1; c < k; ++c)
            values["f_rest_" + std::to_string(a * (k - 1) + c - 1)] = cloud.sh[i * k * 3 + c * 3 + a];
    }
    for (size_t a = 0; a < 4; ++a) values["rot_" + std::to_string(a)] = cloud.rotations[i * 4 + a];
    values["opacity"] = cloud.opacity_logits[i];
    return values;
}

}  // namespace vksplat::io::test
