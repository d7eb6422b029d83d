// PlayCanvas's compressed PLY: splats in chunks of 256, each chunk giving the range of its
// positions, log scales (and colours), each splat packing its values into 32-bit words relative to
// its chunk's range, with the higher SH as bytes in a third element.
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <optional>

#include "io/byte_order.hpp"
#include "io/compressed_ply_layout.hpp"
#include "io/formats_detail.hpp"
#include "io/ply_header.hpp"
#include "vksplat/io/formats.hpp"

namespace vksplat::io {
namespace {

namespace fs = std::filesystem;
using ply::ScalarType;

using namespace compressed_ply;

double load_as_double(const char* bytes, ScalarType type, bool swap) {
    using detail::load_scalar;
    switch (type) {
        case ScalarType::int8:
            return load_scalar<int8_t>(bytes, swap);
        case ScalarType::uint8:
            return load_scalar<uint8_t>(bytes, swap);
        case ScalarType::int16:
            return load_scalar<int16_t>(bytes, swap);
        case ScalarType::uint16:
            return load_scalar<uint16_t>(bytes, swap);
        case ScalarType::int32:
            return load_scalar<int32_t>(bytes, swap);
        case ScalarType::uint32:
            return load_scalar<uint32_t>(bytes, swap);
        case ScalarType::float32:
            return load_scalar<float>(bytes, swap);
        case ScalarType::float64:
            return load_scalar<double>(bytes, swap);
    }
    return 0;
}

// One element's rows in memory, with its properties found by name.
struct Table {
    const ply::Element* element = nullptr;
    std::string at;  // "<file>: element '<name>'"
    std::string rows;
    size_t stride = 0;
    bool swap = false;

    struct Column {
        size_t offset = 0;
        ScalarType type = ScalarType::float32;
    };

    std::optional<Column> find(const std::string& name) const {
        size_t offset = 0;
        for (const auto& property : element->properties) {
            if (property.name == name) return Column{offset, property.type};
            offset += ply::scalar_size(property.type);
        }
        return std::nullopt;
    }
    Column require(const std::string& name) const {
        const auto column = find(name);
        if (!column) throw InputError(at, "missing required property " + name);
        return *column;
    }
    Column require_type(const std::string& name, ScalarType type, const char* type_name) const {
        const Column column = require(name);
        if (column.type != type) throw InputError(at, "property " + name + " must be " + type_name);
        return column;
    }
    double value(size_t row, const Column& column) const {
        return load_as_double(rows.data() + row * stride + column.offset, column.type, swap);
    }
    uint32_t word(size_t row, const Column& column) const {
        return detail::load_scalar<uint32_t>(rows.data() + row * stride + column.offset, swap);
    }
    uint8_t byte(size_t row, const Column& column) const {
        return static_cast<uint8_t>(rows[row * stride + column.offset]);
    }
};

double unorm(uint32_t value, int bits) {
    const uint32_t mask = (1u << bits) - 1u;
    return static_cast<double>(value & mask) / mask;
}

double lerp(double a, double b, double t) { return a * (1 - t) + b * t; }

bool header_is_compressed(const ply::Header& header) {
    bool has_chunk = false, has_packed = false;
    for (const auto& element : header.elements) {
        if (element.name == "chunk") has_chunk = true;
        if (element.name == "vertex")
            for (const auto& property : element.properties)
                if (property.name == "packed_position") has_packed = true;
    }
    return has_chunk && has_packed;
}

}  // namespace

bool is_compressed_ply(const fs::path& path) {
    const std::string where = path.string();
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(where, fs::exists(path) ? "cannot be opened" : "no such file");
    return header_is_compressed(ply::read_header(in, where));
}

GaussianCloud read_compressed_ply(const fs::path& path, std::vector<std::string>* notes) {
    const std::string where = path.string();
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(where, fs::exists(path) ? "cannot be opened" : "no such file");
    const uint64_t file_size = fs::file_size(path);
    const ply::Header header = ply::read_header(in, where);
    if (header.format == ply::Format::ascii)
        throw InputError(where, "a compressed PLY must be binary, not ASCII");
    const bool swap = (header.format == ply::Format::binary_little_endian) != detail::kHostIsLittleEndian;

    // Every element is read (its rows are few bytes each) or skipped; lists cannot be located.
    std::map<std::string, Table> tables;
    std::vector<std::string> skipped;
    uint64_t offset = header.body_offset;
    for (const auto& element : header.elements) {
        const std::string at = where + ": element '" + element.name + "'";
        if (element.has_list()) throw InputError(at, "has a list property, which a compressed PLY never has");
        const uint64_t stride = element.fixed_stride();
        uint64_t bytes = 0;
        if (__builtin_mul_overflow(element.count, stride, &bytes))
            throw InputError(at, "count " + std::to_string(element.count) + " overflows (times " +
                                     std::to_string(stride) + " bytes each)");
        if (bytes > file_size - offset)
            throw InputError(at, "truncated: " + std::to_string(element.count) + " items need " +
                                     std::to_string(bytes) + " bytes but only " + std::to_string(file_size - offset) +
                                     " remain");
        const bool wanted = element.name == "chunk" || element.name == "vertex" || element.name == "sh";
        if (wanted && !tables.count(element.name)) {
            Table table;
            table.element = &element;
            table.at = at;
            table.stride = stride;
            table.swap = swap;
            table.rows.resize(bytes);
            in.seekg(static_cast<std::streamoff>(offset));
            if (!in.read(table.rows.data(), static_cast<std::streamsize>(bytes)))
                throw InputError(at, "reading " + std::to_string(bytes) + " bytes failed");
            tables.emplace(element.name, std::move(table));
        } else {
            skipped.push_back(element.name + " (" + std::to_string(element.count) + ")");
        }
        offset += bytes;
    }
    if (!tables.count("chunk")) throw InputError(where, "not a compressed PLY: it has no 'chunk' element");
    if (!tables.count("vertex")) throw InputError(where, "has no 'vertex' element");
    const Table& chunks = tables.at("chunk");
    const Table& vertices = tables.at("vertex");
    const uint64_t count = vertices.element->count;
    const uint64_t chunk_count = chunks.element->count;
    const uint64_t chunks_needed = count / kChunkSize + (count % kChunkSize ? 1 : 0);
    if (chunk_count != chunks_needed)
        throw InputError(chunks.at, "has " + std::to_string(chunk_count) + " chunks but " + std::to_string(count) +
                                        " vertices need " + std::to_string(chunks_needed) + " (one per 256)");

    std::vector<Table::Column> range;
    for (const char* name : kChunkGeometryFields) range.push_back(chunks.require(name));
    size_t colour_fields = 0;
    for (const char* name : kChunkColourFields) colour_fields += chunks.find(name) ? 1 : 0;
    if (colour_fields != 0 && colour_fields != std::size(kChunkColourFields))
        throw InputError(chunks.at, "has some but not all of the colour range properties min_r..max_b");
    const bool chunk_colours = colour_fields != 0;
    if (chunk_colours)
        for (const char* name : kChunkColourFields) range.push_back(chunks.require(name));
    std::vector<Table::Column> packed;
    for (const char* name : kVertexFields) packed.push_back(vertices.require_type(name, ScalarType::uint32, "uint"));

    // Higher SH: f_rest_* bytes, channel-major as in the INRIA layout.
    int sh_degree = 0;
    std::vector<Table::Column> rest;
    const Table* sh_table = tables.count("sh") ? &tables.at("sh") : nullptr;
    if (sh_table) {
        const size_t rest_count = sh_table->element->properties.size();
        switch (rest_count) {
            case 9:
                sh_degree = 1;
                break;
            case 24:
                sh_degree = 2;
                break;
            case 45:
                sh_degree = 3;
                break;
            default:
                throw InputError(sh_table->at, "has " + std::to_string(rest_count) +
                                                   " properties; expected 9, 24 or 45 (f_rest_* for SH degree 1 to 3)");
        }
        if (sh_table->element->count != count)
            throw InputError(sh_table->at, "has " + std::to_string(sh_table->element->count) + " rows but there are " +
                                               std::to_string(count) + " vertices");
        for (size_t r = 0; r < rest_count; ++r)
            rest.push_back(sh_table->require_type("f_rest_" + std::to_string(r), ScalarType::uint8, "uchar"));
    }

    GaussianCloud cloud;
    cloud.sh_degree = sh_degree;
    cloud.resize(count);
    const size_t coefficients = static_cast<size_t>(cloud.sh_coefficients());
    const size_t rest_per_channel = coefficients - 1;
    std::vector<double> bounds(range.size());
    for (size_t i = 0; i < count; ++i) {
        if (i % kChunkSize == 0)
            for (size_t b = 0; b < range.size(); ++b) bounds[b] = chunks.value(i / kChunkSize, range[b]);
        const uint32_t position = vertices.word(i, packed[0]);
        const uint32_t rotation = vertices.word(i, packed[1]);
        const uint32_t scale = vertices.word(i, packed[2]);
        const uint32_t colour = vertices.word(i, packed[3]);

        // Positions and scales are 11-10-11 bits (x in the highest) across the chunk's range.
        const double position_t[3] = {unorm(position >> 21, 11), unorm(position >> 11, 10), unorm(position, 11)};
        const double scale_t[3] = {unorm(scale >> 21, 11), unorm(scale >> 11, 10), unorm(scale, 11)};
        for (size_t a = 0; a < 3; ++a) {
            cloud.positions[i * 3 + a] = static_cast<float>(lerp(bounds[a], bounds[3 + a], position_t[a]));
            cloud.log_scales[i * 3 + a] = static_cast<float>(lerp(bounds[6 + a], bounds[9 + a], scale_t[a]));
        }

        // Rotation: the index of the largest component (in rot_0..rot_3 order, i.e. w, x, y, z) in
        // the top two bits, the other three in 10 bits each, in units of sqrt(2) around 0.5.
        const double norm = std::sqrt(2.0);
        const double small[3] = {(unorm(rotation >> 20, 10) - 0.5) * norm, (unorm(rotation >> 10, 10) - 0.5) * norm,
                                 (unorm(rotation, 10) - 0.5) * norm};
        const double largest = std::sqrt(std::max(0.0, 1.0 - (small[0] * small[0] + small[1] * small[1] +
                                                               small[2] * small[2])));
        const uint32_t which = rotation >> 30;
        for (uint32_t a = 0, s = 0; a < 4; ++a)
            cloud.rotations[i * 4 + a] = static_cast<float>(a == which ? largest : small[s++]);

        // Colour: RGBA 8-8-8-8 (red in the highest byte); RGB across the chunk's colour range if any.
        const double rgba[4] = {unorm(colour >> 24, 8), unorm(colour >> 16, 8), unorm(colour >> 8, 8),
                                unorm(colour, 8)};
        for (size_t a = 0; a < 3; ++a) {
            const double c = chunk_colours ? lerp(bounds[12 + a], bounds[15 + a], rgba[a]) : rgba[a];
            cloud.sh[i * coefficients * 3 + a] = static_cast<float>((c - 0.5) / detail::kShC0);
        }
        const double alpha = rgba[3];
        cloud.opacity_logits[i] =
            (alpha <= 0 || alpha >= 1) ? detail::logit_of(alpha) : static_cast<float>(-std::log(1.0 / alpha - 1.0));

        // SH bytes: 0 and 255 are the ends of [-4, 4]; others the centres of 256 buckets.
        for (size_t r = 0; r < rest.size(); ++r) {
            const uint8_t v = sh_table->byte(i, rest[r]);
            const double unit = v == 0 ? 0.0 : v == 255 ? 1.0 : (v + 0.5) / 256.0;
            const size_t channel = r / rest_per_channel;
            const size_t coefficient = 1 + r % rest_per_channel;
            cloud.sh[i * coefficients * 3 + coefficient * 3 + channel] = static_cast<float>((unit - 0.5) * 8.0);
        }
    }
    if (notes && !skipped.empty()) {
        std::string list;
        for (const auto& name : skipped) list += (list.empty() ? "" : ", ") + name;
        notes->push_back(where + ": skipped elements " + list);
    }
    return cloud;
}

}  // namespace vksplat::io
