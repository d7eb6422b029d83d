// Parses the text header that every PLY file starts with, whatever the body's format.
#include "io/ply_header.hpp"

#include <charconv>
#include <sstream>

#include "vksplat/error.hpp"

namespace vksplat::io::ply {
namespace {

// Real headers are a few kilobytes; looking no further keeps a binary file without end_header
// from being read whole in search of one.
constexpr size_t kMaxHeaderBytes = 1 << 20;

bool parse_type(const std::string& word, ScalarType& type) {
    struct Alias {
        const char* name;
        ScalarType type;
    };
    static constexpr Alias aliases[] = {
        {"char", ScalarType::int8},       {"int8", ScalarType::int8},       {"uchar", ScalarType::uint8},
        {"uint8", ScalarType::uint8},     {"short", ScalarType::int16},     {"int16", ScalarType::int16},
        {"ushort", ScalarType::uint16},   {"uint16", ScalarType::uint16},   {"int", ScalarType::int32},
        {"int32", ScalarType::int32},     {"uint", ScalarType::uint32},     {"uint32", ScalarType::uint32},
        {"float", ScalarType::float32},   {"float32", ScalarType::float32}, {"double", ScalarType::float64},
        {"float64", ScalarType::float64},
    };
    for (const auto& alias : aliases) {
        if (word == alias.name) {
            type = alias.type;
            return true;
        }
    }
    return false;
}

// A header line as it may be quoted in a message: short, and without control bytes from a body.
std::string quoted_line(const std::string& line) {
    std::string shown;
    for (char c : line.substr(0, 60)) shown += (c >= 32 && c < 127) ? c : '?';
    return "'" + shown + (line.size() > 60 ? "...'" : "'");
}

std::vector<std::string> words_of(const std::string& line) {
    std::istringstream stream(line);
    std::vector<std::string> words;
    for (std::string word; stream >> word;) words.push_back(word);
    return words;
}

}  // namespace

size_t scalar_size(ScalarType type) {
    switch (type) {
        case ScalarType::int8:
        case ScalarType::uint8:
            return 1;
        case ScalarType::int16:
        case ScalarType::uint16:
            return 2;
        case ScalarType::int32:
        case ScalarType::uint32:
        case ScalarType::float32:
            return 4;
        case ScalarType::float64:
            return 8;
    }
    return 0;
}

bool Element::has_list() const {
    for (const auto& property : properties)
        if (property.is_list) return true;
    return false;
}

size_t Element::fixed_stride() const {
    size_t stride = 0;
    for (const auto& property : properties) stride += scalar_size(property.type);
    return stride;
}

Header read_header(std::istream& in, const std::string& where) {
    std::string text(kMaxHeaderBytes, '\0');
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    text.resize(static_cast<size_t>(in.gcount()));
    in.clear();

    Header header;
    bool seen_format = false;
    size_t line_start = 0;
    for (size_t line_number = 1;; ++line_number) {
        const size_t line_end = text.find('\n', line_start);
        if (line_end == std::string::npos) {
            if (line_number == 1 && text.rfind("ply", 0) != 0)
                throw InputError(where, "not a PLY file (it does not start with 'ply')");
            throw InputError(where, text.size() >= kMaxHeaderBytes ? "header has no end_header in its first 1 MiB"
                                                                   : "header has no end_header (the file ends first)");
        }
        std::string line = text.substr(line_start, line_end - line_start);
        if (!line.empty() && line.back() == '\r') line.pop_back();  // written on Windows
        line_start = line_end + 1;

        const std::string at = "header line " + std::to_string(line_number) + ": ";
        if (line_number == 1) {
            if (line != "ply") throw InputError(where, "not a PLY file (it does not start with 'ply')");
            continue;
        }
        const auto words = words_of(line);
        if (words.empty()) continue;
        const std::string& keyword = words[0];
        if (keyword == "end_header") {
            if (!seen_format) throw InputError(where, "header has no format line");
            header.body_offset = line_start;
            header.line_count = line_number;
            return header;
        }
        if (keyword == "comment" || keyword == "obj_info") continue;
        if (keyword == "format") {
            if (words.size() != 3) throw InputError(where, at + "malformed format line " + quoted_line(line));
            if (words[1] == "ascii")
                header.format = Format::ascii;
            else if (words[1] == "binary_little_endian")
                header.format = Format::binary_little_endian;
            else if (words[1] == "binary_big_endian")
                header.format = Format::binary_big_endian;
            else
                throw InputError(where, at + "unsupported format '" + words[1] + "'");
            seen_format = true;
        } else if (keyword == "element") {
            if (words.size() != 3) throw InputError(where, at + "malformed element line " + quoted_line(line));
            Element element;
            element.name = words[1];
            const auto& count = words[2];
            const auto result = std::from_chars(count.data(), count.data() + count.size(), element.count);
            if (result.ec != std::errc() || result.ptr != count.data() + count.size())
                throw InputError(where, "element '" + element.name + "': count '" + count +
                                            "' is not a number that fits in 64 bits");
            header.elements.push_back(std::move(element));
        } else if (keyword == "property") {
            if (header.elements.empty())
                throw InputError(where, at + "property before any element: " + quoted_line(line));
            Element& element = header.elements.back();
            Property property;
            const bool is_list = words.size() == 5 && words[1] == "list";
            if (!is_list && words.size() != 3)
                throw InputError(where,
                                 "element '" + element.name + "': " + at + "malformed property line " +
                                     quoted_line(line));
            property.is_list = is_list;
            property.name = words.back();
            const std::string& type = words[is_list ? 3 : 1];
            if (!parse_type(type, property.type) || (is_list && !parse_type(words[2], property.count_type)))
                throw InputError(where, "element '" + element.name + "': property '" + property.name +
                                            "' has an unknown type in " + quoted_line(line));
            for (const auto& existing : element.properties)
                if (existing.name == property.name)
                    throw InputError(
                        where, "element '" + element.name + "': property '" + property.name + "' is declared twice");
            element.properties.push_back(std::move(property));
        } else {
            throw InputError(where, at + "unrecognised header line " + quoted_line(line) + " (is end_header missing?)");
        }
    }
}

}  // namespace vksplat::io::ply
