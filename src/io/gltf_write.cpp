// Writes a cloud as a binary glTF (.glb) whose one point primitive carries KHR_gaussian_splatting.
#include <nlohmann/json.hpp>

#include <cmath>
#include <limits>

#include "io/formats_detail.hpp"
#include "io/gltf_layout.hpp"
#include "vksplat/io/formats.hpp"

namespace vksplat::io {
namespace {

namespace gltf = detail::gltf;

// One attribute: its accessor's description and its bytes in the BIN chunk.
struct Attribute {
    std::string name;
    std::string type;  // SCALAR, VEC3, VEC4
    int component_type = gltf::kFloat;
    bool normalized = false;
    std::string bytes;
};

// COLOR_0 holds linear values while the splats' colours are sRGB-encoded (the extension's
// colorSpace srgb_rec709_display), so the fallback colour is decoded as the extension's note asks.
double srgb_to_linear(double encoded) {
    return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

std::vector<Attribute> attributes_of(const GaussianCloud& cloud, const std::string& where) {
    const size_t n = cloud.size(), stride = size_t(cloud.sh_coefficients()) * 3;
    Attribute position{"POSITION", "VEC3"}, color{"COLOR_0", "VEC4", gltf::kUnsignedByte, true},
        rotation{gltf::kRotation, "VEC4"}, scale{gltf::kScale, "VEC3"}, opacity{gltf::kOpacity, "SCALAR"};
    for (size_t i = 0; i < n; ++i) {
        for (size_t a = 0; a < 3; ++a) {
            const float p = gltf::kTurnPosition[a] * cloud.positions[i * 3 + a];
            if (!std::isfinite(p))
                throw InputError(where, "cannot write Gaussian " + std::to_string(i) +
                                            ": its position is not finite (glTF needs finite bounds)");
            detail::store_little_endian(position.bytes, p);
            detail::store_little_endian(scale.bytes, static_cast<float>(std::exp(double(cloud.log_scales[i * 3 + a]))));
        }
        // The extension asks for unit quaternions, so renderers need not normalise.
        const float* q = &cloud.rotations[i * 4];
        const double norm = std::sqrt(double(q[0]) * q[0] + double(q[1]) * q[1] + double(q[2]) * q[2] + double(q[3]) * q[3]);
        if (!(norm > 0) || !std::isfinite(norm))
            throw InputError(where, "cannot write Gaussian " + std::to_string(i) +
                                        ": its quaternion has length 0 or is not finite");
        const auto unit = [&](size_t a) { return static_cast<float>(q[a] / norm); };
        for (float v : gltf::turned_to_gltf(unit(0), unit(1), unit(2), unit(3))) detail::store_little_endian(rotation.bytes, v);
        const double alpha = detail::sigmoid(cloud.opacity_logits[i]);
        detail::store_little_endian(opacity.bytes, static_cast<float>(alpha));
        for (size_t a = 0; a < 3; ++a)
            color.bytes += static_cast<char>(detail::to_byte(
                255.0 * srgb_to_linear(std::clamp(0.5 + detail::kShC0 * cloud.sh[i * stride + a], 0.0, 1.0))));
        color.bytes += static_cast<char>(detail::to_byte(255.0 * alpha));
    }
    std::vector<Attribute> attributes{position, color, rotation, scale, opacity};
    for (int degree = 0; degree <= cloud.sh_degree; ++degree)
        for (int order = 0; order <= 2 * degree; ++order) {
            Attribute coefficient{gltf::sh_attribute(degree, order), "VEC3"};
            const size_t k = size_t(degree * degree + order);
            const float sign = k == 0 ? 1.0f : gltf::kTurnSh[k - 1];
            for (size_t i = 0; i < n; ++i)
                for (size_t c = 0; c < 3; ++c)
                    detail::store_little_endian(coefficient.bytes, sign * cloud.sh[i * stride + k * 3 + c]);
            attributes.push_back(std::move(coefficient));
        }
    return attributes;
}

void store_u32(std::string& out, uint64_t value) { detail::store_little_endian(out, static_cast<uint32_t>(value)); }

}  // namespace

void write_gltf(const GaussianCloud& cloud, const std::filesystem::path& path, WriteMode mode) {
    const std::string where = path.string();
    detail::check_writable(cloud, where);
    // The schema wants every accessor to hold at least one element.
    if (cloud.empty()) throw InputError(where, "cannot write an empty scene as glTF (accessors need at least one element)");
    const std::vector<Attribute> attributes = attributes_of(cloud, where);

    nlohmann::ordered_json views = nlohmann::json::array(), accessors = nlohmann::json::array();
    nlohmann::ordered_json primitive_attributes = nlohmann::json::object();
    std::string bin;
    for (const Attribute& attribute : attributes) {
        // Every attribute takes a multiple of 4 bytes (COLOR_0 too: 4 bytes a splat), so each view
        // starts 4-byte aligned, as glTF requires of float accessors.
        nlohmann::ordered_json view{{"buffer", 0}, {"byteOffset", bin.size()},
                                    {"byteLength", attribute.bytes.size()}, {"target", gltf::kTargetArrayBuffer}};
        nlohmann::ordered_json accessor{{"bufferView", views.size()}, {"componentType", attribute.component_type}};
        if (attribute.normalized) accessor["normalized"] = true;
        accessor["count"] = cloud.size();
        accessor["type"] = attribute.type;
        if (attribute.name == "POSITION") {  // bounds: required of POSITION
            std::vector<float> low(3, std::numeric_limits<float>::infinity()), high(3, -low[0]);
            for (size_t i = 0; i < cloud.size(); ++i)
                for (size_t a = 0; a < 3; ++a) {
                    const float p = gltf::kTurnPosition[a] * cloud.positions[i * 3 + a];
                    low[a] = std::min(low[a], p);
                    high[a] = std::max(high[a], p);
                }
            accessor["min"] = low;
            accessor["max"] = high;
        }
        primitive_attributes[attribute.name] = accessors.size();
        views.push_back(std::move(view));
        accessors.push_back(std::move(accessor));
        bin += attribute.bytes;
    }
    // No node transform: the splats are turned into glTF's axes themselves (gltf_layout.hpp).
    const nlohmann::ordered_json document{
        {"asset", {{"version", "2.0"}, {"generator", "vksplat"}}},
        {"extensionsUsed", {gltf::kExtension}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"mesh", 0}}}},
        {"meshes",
         {{{"primitives",
            {{{"attributes", primitive_attributes},
              {"mode", gltf::kModePoints},
              {"extensions",
               {{gltf::kExtension,
                 {{"kernel", "ellipse"}, {"colorSpace", "srgb_rec709_display"}, {"projection", "perspective"},
                  {"sortingMethod", "cameraDistance"}}}}}}}}}}},
        {"accessors", accessors},
        {"bufferViews", views},
        {"buffers", {{{"byteLength", bin.size()}}}},
    };
    std::string json = document.dump();
    json.resize((json.size() + 3) / 4 * 4, ' ');
    bin.resize((bin.size() + 3) / 4 * 4, '\0');
    const uint64_t total = gltf::kHeaderBytes + 2 * gltf::kChunkHeaderBytes + json.size() + bin.size();
    if (total > std::numeric_limits<uint32_t>::max())
        throw InputError(where, "cannot write " + std::to_string(cloud.size()) + " Gaussians as .glb: " +
                                    std::to_string(total) + " bytes exceed the format's 4 GiB limit");
    write_file_atomically(path, mode, [&](std::ostream& out) {
        std::string head;
        store_u32(head, gltf::kMagic);
        store_u32(head, gltf::kVersion);
        store_u32(head, total);
        store_u32(head, json.size());
        store_u32(head, gltf::kChunkJson);
        out << head << json;
        head.clear();
        store_u32(head, bin.size());
        store_u32(head, gltf::kChunkBin);
        out << head << bin;
    });
}

}  // namespace vksplat::io
