// Reads an INRIA 3DGS PLY into a GaussianCloud. The binary body of the vertex element is read in one
// go and converted row by row through a table that sends each property to its place in the cloud.
#include <charconv>
#include <fstream>
#include <memory>
#include <string_view>

#include "io/byte_order.hpp"
#include "io/ply_header.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/ply.hpp"

namespace vksplat::io {
namespace {

namespace fs = std::filesystem;
using ply::Element;
using ply::ScalarType;

// Where one vertex property goes: cloud.*array[gaussian * per_gaussian + component].
struct Target {
    size_t property = 0;  // index among the vertex element's properties
    std::vector<float> GaussianCloud::*array = nullptr;
    size_t per_gaussian = 0;
    size_t component = 0;
};

struct VertexPlan {
    int sh_degree = 0;
    std::vector<Target> targets;
    std::vector<std::string> ignored;  // properties the cloud has no place for
};

struct NamedField {
    const char* name;
    std::vector<float> GaussianCloud::*array;
    size_t per_gaussian;  // 0 for SH: its stride is known once the degree is
    size_t component;
};

// Everything but f_rest, whose place depends on the SH degree.
constexpr NamedField kFixedFields[] = {
    {"x", &GaussianCloud::positions, 3, 0},
    {"y", &GaussianCloud::positions, 3, 1},
    {"z", &GaussianCloud::positions, 3, 2},
    {"f_dc_0", &GaussianCloud::sh, 0, 0},
    {"f_dc_1", &GaussianCloud::sh, 0, 1},
    {"f_dc_2", &GaussianCloud::sh, 0, 2},
    {"opacity", &GaussianCloud::opacity_logits, 1, 0},
    {"scale_0", &GaussianCloud::log_scales, 3, 0},
    {"scale_1", &GaussianCloud::log_scales, 3, 1},
    {"scale_2", &GaussianCloud::log_scales, 3, 2},
    {"rot_0", &GaussianCloud::rotations, 4, 0},
    {"rot_1", &GaussianCloud::rotations, 4, 1},
    {"rot_2", &GaussianCloud::rotations, 4, 2},
    {"rot_3", &GaussianCloud::rotations, 4, 3},
};

// The index in "f_rest_<index>", or -1 for any other name.
long f_rest_index(const std::string& name) {
    constexpr std::string_view prefix = "f_rest_";
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return -1;
    long index = -1;
    const char* end = name.data() + name.size();
    const auto result = std::from_chars(name.data() + prefix.size(), end, index);
    return (result.ec == std::errc() && result.ptr == end) ? index : -1;
}

VertexPlan plan_vertex(const Element& vertex, const std::string& where) {
    const std::string at = where + ": element '" + vertex.name + "'";
    // A list makes vertices vary in size (binary) or in value count (ASCII); no 3DGS file has one.
    for (const auto& property : vertex.properties)
        if (property.is_list) throw InputError(at, "list property '" + property.name + "' is not supported");
    size_t rest_count = 0;
    for (const auto& property : vertex.properties)
        if (f_rest_index(property.name) >= 0) ++rest_count;

    VertexPlan plan;
    switch (rest_count) {
        case 0:
            plan.sh_degree = 0;
            break;
        case 9:
            plan.sh_degree = 1;
            break;
        case 24:
            plan.sh_degree = 2;
            break;
        case 45:
            plan.sh_degree = 3;
            break;
        default:
            throw InputError(at, "has " + std::to_string(rest_count) +
                                     " f_rest_* properties; expected 0, 9, 24 or 45 (SH degree 0 to 3)");
    }
    const size_t coefficients = static_cast<size_t>(sh_coefficients_for_degree(plan.sh_degree));
    const size_t rest_per_channel = coefficients - 1;

    std::vector<bool> fixed_found(std::size(kFixedFields), false);
    std::vector<bool> rest_found(rest_count, false);
    for (size_t p = 0; p < vertex.properties.size(); ++p) {
        const auto& property = vertex.properties[p];
        Target target{p, nullptr, 0, 0};
        if (const long rest = f_rest_index(property.name); rest >= 0) {
            if (static_cast<size_t>(rest) >= rest_count)
                throw InputError(at, "has f_rest_" + std::to_string(rest) + " but only " + std::to_string(rest_count) +
                                         " f_rest_* properties (expected f_rest_0 to f_rest_" +
                                         std::to_string(rest_count - 1) + ")");
            rest_found[static_cast<size_t>(rest)] = true;
            // f_rest is channel-major (all red, then all green, then blue); the cloud is
            // [coefficient][rgb] with the DC term first.
            const size_t channel = static_cast<size_t>(rest) / rest_per_channel;
            const size_t coefficient = 1 + static_cast<size_t>(rest) % rest_per_channel;
            target = {p, &GaussianCloud::sh, coefficients * 3, coefficient * 3 + channel};
        } else {
            for (size_t f = 0; f < std::size(kFixedFields); ++f) {
                if (property.name != kFixedFields[f].name) continue;
                const auto& field = kFixedFields[f];
                const size_t per_gaussian = field.per_gaussian ? field.per_gaussian : coefficients * 3;
                target = {p, field.array, per_gaussian, field.component};
                fixed_found[f] = true;
            }
        }
        if (target.array)
            plan.targets.push_back(target);
        else
            plan.ignored.push_back(property.name);
    }

    std::string missing;
    for (size_t f = 0; f < std::size(kFixedFields); ++f)
        if (!fixed_found[f]) missing += std::string(missing.empty() ? "" : ", ") + kFixedFields[f].name;
    for (size_t r = 0; r < rest_count; ++r)
        if (!rest_found[r]) missing += (missing.empty() ? "f_rest_" : ", f_rest_") + std::to_string(r);
    if (!missing.empty()) throw InputError(at, "missing required property " + missing);
    return plan;
}

template <typename Out>
Out load_as(const char* bytes, ScalarType type, bool swap) {
    using detail::load_scalar;
    switch (type) {
        case ScalarType::int8:
            return static_cast<Out>(load_scalar<int8_t>(bytes, swap));
        case ScalarType::uint8:
            return static_cast<Out>(load_scalar<uint8_t>(bytes, swap));
        case ScalarType::int16:
            return static_cast<Out>(load_scalar<int16_t>(bytes, swap));
        case ScalarType::uint16:
            return static_cast<Out>(load_scalar<uint16_t>(bytes, swap));
        case ScalarType::int32:
            return static_cast<Out>(load_scalar<int32_t>(bytes, swap));
        case ScalarType::uint32:
            return static_cast<Out>(load_scalar<uint32_t>(bytes, swap));
        case ScalarType::float32:
            return static_cast<Out>(load_scalar<float>(bytes, swap));
        case ScalarType::float64:
            return static_cast<Out>(load_scalar<double>(bytes, swap));
    }
    return Out{};
}

// count * size, or throws if it does not fit in 64 bits.
uint64_t checked_product(uint64_t count, uint64_t size, const std::string& at) {
    uint64_t product = 0;
    if (__builtin_mul_overflow(count, size, &product))
        throw InputError(
            at, "count " + std::to_string(count) + " overflows (times " + std::to_string(size) + " bytes each)");
    return product;
}

// Skips a binary element that precedes the vertices; returns the offset just past it.
uint64_t skip_binary_element(std::istream& in, const Element& element, uint64_t offset, uint64_t file_size, bool swap,
                             const std::string& where) {
    const std::string at = where + ": element '" + element.name + "'";
    if (!element.has_list()) {
        const uint64_t bytes = checked_product(element.count, element.fixed_stride(), at);
        if (bytes > file_size - offset)
            throw InputError(at, "truncated: " + std::to_string(element.count) + " items need " +
                                     std::to_string(bytes) + " bytes but only " + std::to_string(file_size - offset) +
                                     " remain");
        return offset + bytes;
    }
    // Lists make items vary in size: walk them, reading each list's length.
    const auto truncated = [&](uint64_t item) {
        return InputError(at, "truncated: the file ends inside item " + std::to_string(item) + " of " +
                                  std::to_string(element.count));
    };
    in.seekg(static_cast<std::streamoff>(offset));
    for (uint64_t item = 0; item < element.count; ++item) {
        for (const auto& property : element.properties) {
            uint64_t skip = ply::scalar_size(property.type);
            if (property.is_list) {
                char length_bytes[8];
                if (!in.read(length_bytes, static_cast<std::streamsize>(ply::scalar_size(property.count_type))))
                    throw truncated(item);
                const double length = load_as<double>(length_bytes, property.count_type, swap);
                if (length < 0)
                    throw InputError(
                        at, "item " + std::to_string(item) + ": list '" + property.name + "' has negative length");
                skip = checked_product(static_cast<uint64_t>(length), skip, at);
            }
            if (skip > file_size || !in.ignore(static_cast<std::streamsize>(skip)) ||
                static_cast<uint64_t>(in.gcount()) != skip)
                throw truncated(item);
        }
    }
    return static_cast<uint64_t>(in.tellg());
}

// Reads the vertices at `offset`; returns the offset just past them.
uint64_t read_binary_vertices(std::istream& in, const Element& vertex, const VertexPlan& plan, uint64_t offset,
                              uint64_t file_size, bool swap, const std::string& where, GaussianCloud& cloud) {
    const std::string at = where + ": element '" + vertex.name + "'";
    const uint64_t available = file_size - offset;
    if (vertex.count > file_size)
        throw InputError(at, "vertex count " + std::to_string(vertex.count) + " is absurd for a file of " +
                                 std::to_string(file_size) + " bytes");
    const size_t stride = vertex.fixed_stride();
    const uint64_t bytes = checked_product(vertex.count, stride, at);
    if (bytes > available)
        throw InputError(at, "truncated body: " + std::to_string(vertex.count) + " vertices expected (" +
                                 std::to_string(bytes) + " bytes, " + std::to_string(stride) + " each) but only " +
                                 std::to_string(available) + " bytes are there (the file ends inside vertex " +
                                 std::to_string(available / stride) + ")");

    cloud.sh_degree = plan.sh_degree;
    cloud.resize(vertex.count);
    const auto body = std::make_unique_for_overwrite<char[]>(bytes);
    in.seekg(static_cast<std::streamoff>(offset));
    if (!in.read(body.get(), static_cast<std::streamsize>(bytes)))
        throw InputError(at, "reading " + std::to_string(bytes) + " bytes of vertices failed");

    std::vector<size_t> offsets;
    for (size_t p = 0, at_byte = 0; p < vertex.properties.size(); ++p) {
        offsets.push_back(at_byte);
        at_byte += ply::scalar_size(vertex.properties[p].type);
    }
    struct Column {
        size_t offset;
        ScalarType type;
        float* out;
        size_t per_gaussian;
    };
    std::vector<Column> columns;
    for (const auto& target : plan.targets)
        columns.push_back({offsets[target.property], vertex.properties[target.property].type,
                           (cloud.*target.array).data() + target.component, target.per_gaussian});
    for (size_t i = 0; i < vertex.count; ++i) {
        const char* row = body.get() + i * stride;
        for (const auto& column : columns)
            column.out[i * column.per_gaussian] = load_as<float>(row + column.offset, column.type, swap);
    }
    return offset + bytes;
}

// Lines of an ASCII body, skipping blank ones, numbered as in the whole file.
class LineCursor {
public:
    LineCursor(std::string_view text, size_t first_line_number) : text_(text), number_(first_line_number - 1) {}
    bool next(std::string_view& line) {
        while (position_ < text_.size()) {
            size_t end = text_.find('\n', position_);
            if (end == std::string_view::npos) end = text_.size();
            line = text_.substr(position_, end - position_);
            position_ = end + 1;
            ++number_;
            if (line.find_first_not_of(" \t\r") != std::string_view::npos) return true;
        }
        return false;
    }
    size_t number() const { return number_; }

private:
    std::string_view text_;
    size_t position_ = 0;
    size_t number_;
};

void read_ascii_vertices(LineCursor& lines, const Element& vertex, const VertexPlan& plan, uint64_t body_bytes,
                         const std::string& where, GaussianCloud& cloud) {
    const std::string at = where + ": element '" + vertex.name + "'";
    const size_t values = vertex.properties.size();
    if (vertex.count > body_bytes)
        throw InputError(at, "vertex count " + std::to_string(vertex.count) + " is absurd for a body of " +
                                 std::to_string(body_bytes) + " bytes");
    // A vertex of n values takes at least 2n - 1 bytes (digits and separators): checked before the
    // cloud is allocated.
    const uint64_t fit = body_bytes / (2 * values - 1);
    if (vertex.count > fit)
        throw InputError(at, "truncated body: " + std::to_string(vertex.count) + " vertices expected but the " +
                                 std::to_string(body_bytes) + " bytes after the header hold at most " +
                                 std::to_string(fit) + " vertices of " + std::to_string(values) + " values");
    cloud.sh_degree = plan.sh_degree;
    cloud.resize(vertex.count);
    std::vector<const Target*> target_of(values, nullptr);
    for (const auto& target : plan.targets) target_of[target.property] = &target;

    std::string_view line;
    for (size_t i = 0; i < vertex.count; ++i) {
        if (!lines.next(line))
            throw InputError(at, "truncated body: " + std::to_string(vertex.count) +
                                     " vertices expected but the file ends after " + std::to_string(i));
        const std::string line_at = "line " + std::to_string(lines.number()) + " (vertex " + std::to_string(i) + ")";
        size_t found = 0;
        for (size_t position = 0;; ++found) {
            position = line.find_first_not_of(" \t\r", position);
            if (position == std::string_view::npos) break;
            size_t end = line.find_first_of(" \t\r", position);
            if (end == std::string_view::npos) end = line.size();
            if (found < values && target_of[found]) {
                const char* first = line.data() + position + (line[position] == '+' ? 1 : 0);
                double value = 0;
                const auto result = std::from_chars(first, line.data() + end, value);
                if (result.ec != std::errc() || result.ptr != line.data() + end)
                    throw InputError(
                        at, line_at + ": '" + std::string(line.substr(position, end - position)) + "' is not a number");
                const Target& target = *target_of[found];
                (cloud.*target.array)[i * target.per_gaussian + target.component] = static_cast<float>(value);
            }
            position = end;
        }
        if (found != values)
            throw InputError(at, line_at + ": has " + std::to_string(found) + " values, expected " +
                                     std::to_string(values) +
                                     (found < values ? " (too few values)" : " (too many values)"));
    }
}

// Data after every element the header declares means the header's counts are wrong (a count
// written too small would otherwise read part of the scene with no word): refused, saying how much
// follows and, where the vertices come last, how many more vertices that is.
InputError trailing_data(const std::string& where, const std::string& amount, const Element& vertex,
                         bool vertex_is_last, const std::string& in_vertices) {
    std::string problem = amount + " follow the end of the body the header declares (" + std::to_string(vertex.count) +
                          " vertices";
    problem += vertex_is_last ? ")" : " and the elements after them)";
    if (vertex_is_last && !in_vertices.empty()) problem += ": " + in_vertices;
    return InputError(where, problem + "; the header's counts disagree with the file (written too small, or the file "
                                       "is damaged)");
}

std::string joined(const std::vector<std::string>& words) {
    std::string text;
    for (const auto& word : words) text += (text.empty() ? "" : ", ") + word;
    return text;
}

}  // namespace

GaussianCloud read_ply(const fs::path& path, std::vector<std::string>* notes) {
    const std::string where = path.string();
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(where, fs::exists(path) ? "cannot be opened" : "no such file");
    const uint64_t file_size = fs::file_size(path);
    const ply::Header header = ply::read_header(in, where);

    size_t vertex_index = header.elements.size();
    for (size_t e = 0; e < header.elements.size() && vertex_index == header.elements.size(); ++e)
        if (header.elements[e].name == "vertex") vertex_index = e;
    if (vertex_index == header.elements.size()) throw InputError(where, "has no 'vertex' element");
    const Element& vertex = header.elements[vertex_index];

    const VertexPlan plan = plan_vertex(vertex, where);
    GaussianCloud cloud;

    if (header.format == ply::Format::ascii) {
        in.seekg(static_cast<std::streamoff>(header.body_offset));
        std::string body(file_size - header.body_offset, '\0');
        in.read(body.data(), static_cast<std::streamsize>(body.size()));
        LineCursor lines(body, header.line_count + 1);
        std::string_view line;
        for (size_t e = 0; e < vertex_index; ++e) {
            // ASCII items are one per line; only counting lines is needed to pass them.
            for (uint64_t item = 0; item < header.elements[e].count; ++item)
                if (!lines.next(line))
                    throw InputError(where + ": element '" + header.elements[e].name + "'",
                                     "truncated: the file ends at item " + std::to_string(item) + " of " +
                                         std::to_string(header.elements[e].count));
        }
        read_ascii_vertices(lines, vertex, plan, body.size(), where, cloud);
        for (size_t e = vertex_index + 1; e < header.elements.size(); ++e)
            for (uint64_t item = 0; item < header.elements[e].count; ++item)
                if (!lines.next(line))
                    throw InputError(where + ": element '" + header.elements[e].name + "'",
                                     "truncated: the file ends at item " + std::to_string(item) + " of " +
                                         std::to_string(header.elements[e].count));
        if (lines.next(line)) {
            const size_t first = lines.number();
            size_t extra = 1;
            while (lines.next(line)) ++extra;
            throw trailing_data(where, std::to_string(extra) + " more lines (from line " + std::to_string(first) + ")",
                                vertex, vertex_index + 1 == header.elements.size(), "");
        }
    } else {
        const bool file_little_endian = header.format == ply::Format::binary_little_endian;
        const bool swap = file_little_endian != detail::kHostIsLittleEndian;
        uint64_t offset = header.body_offset;
        for (size_t e = 0; e < vertex_index; ++e)
            offset = skip_binary_element(in, header.elements[e], offset, file_size, swap, where);
        offset = read_binary_vertices(in, vertex, plan, offset, file_size, swap, where, cloud);
        for (size_t e = vertex_index + 1; e < header.elements.size(); ++e)
            offset = skip_binary_element(in, header.elements[e], offset, file_size, swap, where);
        if (offset < file_size) {
            const uint64_t extra = file_size - offset, stride = vertex.fixed_stride();
            throw trailing_data(where, std::to_string(extra) + " bytes", vertex,
                                vertex_index + 1 == header.elements.size(),
                                "room for " + std::to_string(extra / stride) + " more vertices of " +
                                    std::to_string(stride) + " bytes" +
                                    (extra % stride ? " and " + std::to_string(extra % stride) + " bytes more" : ""));
        }
    }

    if (notes) {
        if (!plan.ignored.empty())
            notes->push_back(where + ": ignored vertex properties " + joined(plan.ignored) +
                             " (a Gaussian cloud has no place for them)");
        std::vector<std::string> skipped;
        for (size_t e = 0; e < header.elements.size(); ++e)
            if (e != vertex_index)
                skipped.push_back(header.elements[e].name + " (" + std::to_string(header.elements[e].count) + ")");
        if (!skipped.empty()) notes->push_back(where + ": skipped elements " + joined(skipped));
    }
    return cloud;
}

}  // namespace vksplat::io
