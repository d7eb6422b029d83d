// Reads the Gaussians of a binary glTF (.glb): every point primitive with KHR_gaussian_splatting.
#include <nlohmann/json.hpp>

#include <cmath>
#include <set>

#include "io/byte_order.hpp"
#include "io/formats_detail.hpp"
#include "io/gltf_layout.hpp"
#include "vksplat/io/formats.hpp"

namespace vksplat::io {
namespace {

namespace gltf = detail::gltf;
using Json = nlohmann::json;

struct Glb {
    Json document;
    std::string_view bin;  // empty when the file has no BIN chunk
};

uint32_t u32_at(const std::string& bytes, size_t offset) { return detail::load_little_endian<uint32_t>(bytes.data() + offset); }

Glb split_glb(const std::string& bytes, const std::string& where) {
    if (bytes.size() < gltf::kHeaderBytes)
        throw InputError(where, "truncated: " + std::to_string(bytes.size()) + " bytes, shorter than the 12-byte GLB header");
    if (u32_at(bytes, 0) != gltf::kMagic)
        throw InputError(where, "not a binary glTF: wrong magic (expected \"glTF\"; a .gltf JSON file is not read, "
                                "only .glb)");
    if (u32_at(bytes, 4) != gltf::kVersion)
        throw InputError(where, "unsupported GLB version " + std::to_string(u32_at(bytes, 4)) + " (only 2 is read)");
    if (u32_at(bytes, 8) != bytes.size())
        throw InputError(where, (u32_at(bytes, 8) > bytes.size() ? "truncated: the header says " : "the header says ") +
                                    std::to_string(u32_at(bytes, 8)) + " bytes, the file has " +
                                    std::to_string(bytes.size()));
    Glb glb;
    bool have_json = false;
    for (size_t offset = gltf::kHeaderBytes; offset < bytes.size();) {
        const std::string chunk = "chunk at byte " + std::to_string(offset);
        if (bytes.size() - offset < gltf::kChunkHeaderBytes)
            throw InputError(where, "truncated: the " + chunk + " has no room for its 8-byte header");
        const uint64_t length = u32_at(bytes, offset), type = u32_at(bytes, offset + 4);
        offset += gltf::kChunkHeaderBytes;
        if (length > bytes.size() - offset)
            throw InputError(where, "truncated: the " + chunk + " says " + std::to_string(length) + " bytes, " +
                                        std::to_string(bytes.size() - offset) + " are left");
        const std::string_view body(bytes.data() + offset, length);
        offset += length;
        if (!have_json) {
            if (type != gltf::kChunkJson) throw InputError(where, "the first chunk is not JSON, as GLB requires");
            try {
                glb.document = Json::parse(body);
            } catch (const Json::exception& error) {
                throw InputError(where, std::string("its JSON chunk is not valid JSON: ") + error.what());
            }
            have_json = true;
        } else if (type == gltf::kChunkBin && glb.bin.empty()) {
            glb.bin = body;
        }  // other chunks: glTF says to ignore them
    }
    if (!have_json) throw InputError(where, "has no JSON chunk");
    return glb;
}

// The JSON value at document[array][index], or an InputError saying which reference is broken.
const Json& element(const Json& document, const char* array, const Json& index, const std::string& where,
                    const std::string& referrer) {
    if (!index.is_number_unsigned() || !document.contains(array) || !document[array].is_array() ||
        index.get<uint64_t>() >= document[array].size())
        throw InputError(where, referrer + " refers to " + array + " " + index.dump() + ", which does not exist");
    return document[array][index.get<size_t>()];
}

size_t components_of(const std::string& type) {
    if (type == "SCALAR") return 1;
    if (type == "VEC3") return 3;
    if (type == "VEC4") return 4;
    return 0;
}

size_t bytes_of(int component_type) {
    switch (component_type) {
        case gltf::kByte: case gltf::kUnsignedByte: return 1;
        case gltf::kShort: case gltf::kUnsignedShort: return 2;
        case gltf::kFloat: return 4;
        default: return 0;
    }
}

// One component as a float; normalised integers as glTF defines them (signed: max(c / max, -1)).
float component_at(const char* at, int component_type, bool normalized) {
    switch (component_type) {
        case gltf::kByte: { const auto c = static_cast<int8_t>(*at); return normalized ? std::max(c / 127.0f, -1.0f) : c; }
        case gltf::kUnsignedByte: { const auto c = static_cast<uint8_t>(*at); return normalized ? c / 255.0f : c; }
        case gltf::kShort: { const auto c = detail::load_little_endian<int16_t>(at); return normalized ? std::max(c / 32767.0f, -1.0f) : c; }
        case gltf::kUnsignedShort: { const auto c = detail::load_little_endian<uint16_t>(at); return normalized ? c / 65535.0f : c; }
        default: return detail::load_little_endian<float>(at);
    }
}

// A primitive's attribute as floats, `count` elements of `type`, checked against the document.
std::vector<float> read_attribute(const Glb& glb, const Json& attributes, const std::string& name,
                                  const std::string& type, const std::set<int>& component_types, size_t count,
                                  const std::string& where) {
    const std::string what = "attribute " + name;
    const Json& accessor = element(glb.document, "accessors", attributes[name], where, what);
    const std::string accessor_name = what + " (accessor " + attributes[name].dump() + ")";
    if (accessor.value("type", "") != type)
        throw InputError(where, accessor_name + " is " + accessor.value("type", "untyped") + ", not " + type);
    const int component_type = accessor.value("componentType", 0);
    if (!component_types.count(component_type))
        throw InputError(where, accessor_name + " has component type " + std::to_string(component_type) +
                                    ", which the extension does not allow there");
    if (accessor.value("count", uint64_t{0}) != count)
        throw InputError(where, accessor_name + " holds " + accessor.value("count", Json(0)).dump() +
                                    " elements where POSITION holds " + std::to_string(count));
    if (accessor.contains("sparse")) throw InputError(where, accessor_name + " is sparse, which is not read");
    if (!accessor.contains("bufferView")) throw InputError(where, accessor_name + " has no bufferView (all zeros)");
    const Json& view = element(glb.document, "bufferViews", accessor["bufferView"], where, accessor_name);
    const Json& buffer = element(glb.document, "buffers", view.value("buffer", Json(-1)), where, accessor_name);
    if (view.value("buffer", 1) != 0 || buffer.contains("uri"))
        throw InputError(where, accessor_name + " lies in an external buffer; only the .glb's own BIN chunk is read");
    const size_t element_bytes = components_of(type) * bytes_of(component_type);
    const uint64_t view_offset = view.value("byteOffset", uint64_t{0}), view_length = view.value("byteLength", uint64_t{0});
    const uint64_t stride = view.value("byteStride", uint64_t{element_bytes});
    const uint64_t start = accessor.value("byteOffset", uint64_t{0});
    // (count - 1) x stride + start + element_bytes <= view_length, checked without overflow: counts,
    // offsets and strides come from the file and may be anything (a count of 0 makes count - 1 the
    // largest value, which fits nowhere).
    const bool fits = stride >= element_bytes && start <= view_length && element_bytes <= view_length - start &&
                      uint64_t(count - 1) <= (view_length - start - element_bytes) / stride;
    if (!fits || view_offset > glb.bin.size() ||
        view_length > glb.bin.size() - view_offset)
        throw InputError(where, accessor_name + " is out of range: it needs " + std::to_string(count) + " elements from byte " +
                                    std::to_string(start) + " of a bufferView of " + std::to_string(view_length) + " bytes at offset " +
                                    std::to_string(view_offset) + ", in a BIN chunk of " +
                                    std::to_string(glb.bin.size()) + " bytes");
    const bool normalized = accessor.value("normalized", false);
    const size_t components = components_of(type), component_bytes = bytes_of(component_type);
    std::vector<float> values(count * components);
    for (size_t i = 0; i < count; ++i) {
        const char* at = glb.bin.data() + view_offset + start + i * stride;
        for (size_t c = 0; c < components; ++c)
            values[i * components + c] = component_at(at + c * component_bytes, component_type, normalized);
    }
    return values;
}

bool is_identity(const Json& node) {
    if (node.contains("matrix") && node["matrix"] != Json{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}) return false;
    if (node.contains("translation") && node["translation"] != Json{0, 0, 0}) return false;
    if (node.contains("rotation") && node["rotation"] != Json{0, 0, 0, 1}) return false;
    return !node.contains("scale") || node["scale"] == Json{1, 1, 1};
}

// Turning splats (and their SH) by a node's transform is not done here: such files are refused
// rather than read in the wrong place.
void check_untransformed(const Json& document, size_t mesh, const std::string& where) {
    if (!document.contains("nodes")) return;
    const Json& nodes = document["nodes"];
    std::vector<size_t> parent(nodes.size(), SIZE_MAX);
    for (size_t i = 0; i < nodes.size(); ++i)
        for (const Json& child : nodes[i].value("children", Json::array()))
            if (child.is_number_unsigned() && child.get<size_t>() < nodes.size()) parent[child.get<size_t>()] = i;
    for (size_t i = 0; i < nodes.size(); ++i) {
        if (nodes[i].value("mesh", Json(-1)) != mesh) continue;
        for (size_t n = i, steps = 0; n != SIZE_MAX && steps <= nodes.size(); n = parent[n], ++steps)
            if (!is_identity(nodes[n]))
                throw InputError(where, "mesh " + std::to_string(mesh) + " is placed by node " + std::to_string(n) +
                                            "'s transform, which is not read (only untransformed splats are)");
    }
}

GaussianCloud read_primitive(const Glb& glb, const Json& primitive, const std::string& name,
                             std::vector<std::string>* notes, const std::string& where) {
    if (primitive.value("mode", 4) != gltf::kModePoints)
        throw InputError(where, name + " has mode " + primitive.value("mode", Json(4)).dump() +
                                    "; KHR_gaussian_splatting needs POINTS (0)");
    const Json& extension = primitive["extensions"][gltf::kExtension];
    const std::string kernel = extension.value("kernel", "");
    if (kernel != "ellipse")
        throw InputError(where, name + " has kernel '" + kernel + "'; only 'ellipse' is read");
    const std::string color_space = extension.value("colorSpace", "");
    if (color_space != "srgb_rec709_display" && notes)
        notes->push_back(where + ": " + name + " has colorSpace '" + color_space +
                         "'; its colours are used as they are, like srgb_rec709_display");
    const Json& attributes = primitive.value("attributes", Json::object());
    const auto require = [&](const std::string& attribute) {
        if (!attributes.contains(attribute))
            throw InputError(where, name + " lacks the attribute " + attribute + ", which the extension requires");
    };
    for (const std::string attribute : {"POSITION", gltf::kRotation, gltf::kScale, gltf::kOpacity})
        require(attribute);
    require(gltf::sh_attribute(0, 0));
    const Json& position_accessor = element(glb.document, "accessors", attributes["POSITION"], where, name + "'s POSITION");
    const size_t count = position_accessor.value("count", size_t{0});
    if (count == 0) throw InputError(where, name + "'s POSITION holds no elements");

    int sh_degree = 0;
    while (sh_degree < 3 && attributes.contains(gltf::sh_attribute(sh_degree + 1, 0))) ++sh_degree;
    for (int degree = 1; degree <= 3; ++degree)
        for (int order = 0; order <= 2 * degree; ++order)
            if (attributes.contains(gltf::sh_attribute(degree, order)) != (degree <= sh_degree))
                throw InputError(where, name + " defines SH degree " + std::to_string(degree) +
                                            " in part: " + gltf::sh_attribute(degree, order) + " is " +
                                            (degree <= sh_degree ? "missing" : "there but a lower degree is not complete"));

    const std::set<int> any = {gltf::kFloat, gltf::kByte, gltf::kUnsignedByte, gltf::kShort, gltf::kUnsignedShort};
    const auto read = [&](const std::string& attribute, const std::string& type, const std::set<int>& types) {
        return read_attribute(glb, attributes, attribute, type, types, count, where);
    };
    const std::vector<float> positions = read("POSITION", "VEC3", any);
    const std::vector<float> rotations = read(gltf::kRotation, "VEC4", {gltf::kFloat, gltf::kByte, gltf::kShort});
    const std::vector<float> scales = read(gltf::kScale, "VEC3", {gltf::kFloat, gltf::kUnsignedByte, gltf::kUnsignedShort});
    const std::vector<float> opacities = read(gltf::kOpacity, "SCALAR", {gltf::kFloat, gltf::kUnsignedByte, gltf::kUnsignedShort});

    GaussianCloud cloud;
    cloud.sh_degree = sh_degree;
    cloud.resize(count);
    for (size_t i = 0; i < positions.size(); ++i) cloud.positions[i] = gltf::kTurnPosition[i % 3] * positions[i];
    const size_t stride = size_t(cloud.sh_coefficients()) * 3;
    for (size_t i = 0; i < count; ++i) {
        for (size_t a = 0; a < 3; ++a) {
            const float scale = scales[i * 3 + a];
            if (!(scale >= 0))
                throw InputError(where, name + ": splat " + std::to_string(i) + " has scale " + std::to_string(scale) +
                                            "; scales are linear and must not be negative");
            cloud.log_scales[i * 3 + a] = scale > 0 ? std::log(scale) : kMinLogScale;
        }
        const float* q = &rotations[i * 4];
        const auto turned = gltf::turned_from_gltf(q[0], q[1], q[2], q[3]);
        std::copy(turned.begin(), turned.end(), cloud.rotations.begin() + std::ptrdiff_t(i * 4));
        if (!(opacities[i] >= 0 && opacities[i] <= 1))
            throw InputError(where, name + ": splat " + std::to_string(i) + " has opacity " +
                                        std::to_string(opacities[i]) + ", outside [0, 1]");
        cloud.opacity_logits[i] = detail::logit_of(opacities[i]);
    }
    for (int degree = 0; degree <= sh_degree; ++degree)
        for (int order = 0; order <= 2 * degree; ++order) {
            const std::vector<float> values = read(gltf::sh_attribute(degree, order), "VEC3", {gltf::kFloat});
            const size_t k = size_t(degree * degree + order);
            const float sign = k == 0 ? 1.0f : gltf::kTurnSh[k - 1];
            for (size_t i = 0; i < count; ++i)
                for (size_t c = 0; c < 3; ++c) cloud.sh[i * stride + k * 3 + c] = sign * values[i * 3 + c];
        }
    return cloud;
}

// Every splat primitive of the document, joined into one cloud.
GaussianCloud splats_of(const Glb& glb, std::vector<std::string>* notes, const std::string& where) {
    const Json& document = glb.document;
    if (!document.is_object()) throw InputError(where, "its JSON chunk is not a JSON object");
    for (const Json& required : document.value("extensionsRequired", Json::array()))
        if (required != gltf::kExtension)
            throw InputError(where, "requires the extension " + required.dump() + ", which is not read");

    std::vector<GaussianCloud> parts;
    const Json& meshes = document.value("meshes", Json::array());
    for (size_t m = 0; m < meshes.size(); ++m) {
        const Json& primitives = meshes[m].value("primitives", Json::array());
        for (size_t p = 0; p < primitives.size(); ++p) {
            if (!primitives[p].contains("extensions") || !primitives[p]["extensions"].contains(gltf::kExtension))
                continue;
            check_untransformed(document, m, where);
            parts.push_back(read_primitive(glb, primitives[p],
                                           "mesh " + std::to_string(m) + " primitive " + std::to_string(p), notes, where));
        }
    }
    if (parts.empty())
        throw InputError(where, std::string("has no mesh primitive with the ") + gltf::kExtension +
                                    " extension: it holds no Gaussian splats");
    int degree = 0;
    bool mixed = false;
    for (const GaussianCloud& part : parts) {
        mixed = mixed || part.sh_degree != parts[0].sh_degree;
        degree = std::max(degree, part.sh_degree);
    }
    if (parts.size() == 1) return std::move(parts[0]);
    GaussianCloud cloud;
    cloud.sh_degree = degree;
    for (const GaussianCloud& part : parts) {
        const GaussianCloud same_degree = part.with_sh_degree(degree);
        for (size_t i = 0; i < same_degree.size(); ++i) cloud.append(same_degree, i);
    }
    if (notes)
        notes->push_back(where + ": " + std::to_string(parts.size()) + " splat primitives joined into one scene" +
                         (mixed ? " (those of lower SH degree padded with zeros)" : ""));
    return cloud;
}

}  // namespace

GaussianCloud read_gltf(const std::filesystem::path& path, std::vector<std::string>* notes) {
    const std::string where = path.string();
    const std::string bytes = detail::read_file_bytes(path, where);
    const Glb glb = split_glb(bytes, where);
    try {
        return splats_of(glb, notes, where);
    } catch (const Json::exception& error) {  // a value of the wrong JSON type somewhere
        throw InputError(where, std::string("malformed glTF JSON: ") + error.what());
    }
}

}  // namespace vksplat::io

