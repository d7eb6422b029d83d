#pragma once
// The header of a PLY file: its format and the elements it declares, in file order.
#include <cstdint>
#include <istream>
#include <string>
#include <vector>

namespace vksplat::io::ply {

enum class Format { ascii, binary_little_endian, binary_big_endian };
enum class ScalarType { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

size_t scalar_size(ScalarType type);

struct Property {
    std::string name;
    ScalarType type = ScalarType::float32;  // for a list: the type of its items
    bool is_list = false;
    ScalarType count_type = ScalarType::uint8;  // for a list: the type of its length
};

struct Element {
    std::string name;
    uint64_t count = 0;
    std::vector<Property> properties;

    bool has_list() const;
    // Bytes one item takes in a binary body (meaningless when has_list()).
    size_t fixed_stride() const;
};

struct Header {
    Format format = Format::ascii;
    std::vector<Element> elements;
    uint64_t body_offset = 0;  // byte at which the body starts
    size_t line_count = 0;     // lines in the header, end_header included
};

// Reads the header from the start of `in`. Throws InputError prefixed with `where` when the file is
// not a PLY, has no end_header, or declares something malformed or unsupported.
Header read_header(std::istream& in, const std::string& where);

}  // namespace vksplat::io::ply
