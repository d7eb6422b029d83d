// The .npy format: a magic string, a version, a Python dict literal describing the array, padded
// so that the data starts on a 64-byte boundary, then the raw elements.
#include "vksplat/io/npy.hpp"

#include <bit>
#include <charconv>
#include <fstream>

#include "io/byte_order.hpp"

namespace vksplat::io {
namespace {

constexpr char kMagic[] = "\x93NUMPY";
constexpr size_t kMagicSize = 6;

// Elements are written and read as the host stores them.
static_assert(std::endian::native == std::endian::little, ".npy files are read and written little-endian");

struct DtypeInfo {
    NpyDtype dtype;
    const char* name;
    const char* descr;  // as NumPy writes it
    size_t size;
};

constexpr DtypeInfo kDtypes[] = {
    {NpyDtype::float32, "float32", "<f4", 4}, {NpyDtype::int32, "int32", "<i4", 4},
    {NpyDtype::int16, "int16", "<i2", 2},     {NpyDtype::uint8, "uint8", "|u1", 1},
    {NpyDtype::uint32, "uint32", "<u4", 4},
};

const DtypeInfo& info(NpyDtype dtype) {
    for (const auto& entry : kDtypes)
        if (entry.dtype == dtype) return entry;
    return kDtypes[0];
}

// The product of the extents, or throws if it overflows.
size_t checked_count(const std::vector<size_t>& shape, size_t element_size, const std::string& where) {
    size_t bytes = element_size;
    for (size_t extent : shape)
        if (__builtin_mul_overflow(bytes, extent, &bytes))
            throw InputError(where, "array shape is too large (overflows)");
    return bytes;
}

std::string shape_text(const std::vector<size_t>& shape) {
    std::string text = "(";
    for (size_t extent : shape) text += std::to_string(extent) + (shape.size() == 1 ? "," : ", ");
    if (shape.size() > 1) text.resize(text.size() - 2);
    return text + ")";
}

// The text of the dict entry `key` (after its colon), trimmed of leading spaces.
std::string_view entry(std::string_view dict, const char* key, const std::string& where) {
    for (const char quote : {'\'', '"'}) {
        const std::string quoted = quote + std::string(key) + quote;
        size_t at = dict.find(quoted);
        if (at == std::string_view::npos) continue;
        at = dict.find(':', at + quoted.size());
        if (at == std::string_view::npos) break;
        at = dict.find_first_not_of(' ', at + 1);
        if (at != std::string_view::npos) return dict.substr(at);
    }
    throw InputError(where, "header has no '" + std::string(key) + "' entry");
}

NpyDtype parse_descr(std::string_view dict, const std::string& where) {
    const std::string_view text = entry(dict, "descr", where);
    const size_t end = text.empty() ? std::string_view::npos : text.find(text[0], 1);
    if (end == std::string_view::npos || (text[0] != '\'' && text[0] != '"'))
        throw InputError(where, "header's 'descr' is not a string");
    const std::string descr(text.substr(1, end - 1));
    if (descr.size() == 3 && descr[0] == '>' && descr[2] != '1')
        throw InputError(where, "holds big-endian data ('" + descr + "'); only little-endian is supported");
    for (const auto& candidate : kDtypes) {
        // A single byte has no byte order: NumPy writes '|u1', others may write '<u1'.
        std::string alternative = candidate.descr;
        if (candidate.size == 1) alternative[0] = '<';
        if (descr == candidate.descr || descr == alternative) return candidate.dtype;
    }
    throw InputError(where, "unsupported dtype '" + descr + "' (supported: float32, int32, int16, uint8, uint32)");
}

std::vector<size_t> parse_shape(std::string_view dict, const std::string& where) {
    std::string_view text = entry(dict, "shape", where);
    const size_t close = text.find(')');
    if (text.empty() || text[0] != '(' || close == std::string_view::npos)
        throw InputError(where, "header's 'shape' is not a tuple");
    text = text.substr(1, close - 1);
    std::vector<size_t> shape;
    while (true) {
        const size_t start = text.find_first_not_of(", ");
        if (start == std::string_view::npos) break;
        size_t extent = 0;
        const auto result = std::from_chars(text.data() + start, text.data() + text.size(), extent);
        if (result.ec != std::errc()) throw InputError(where, "header's 'shape' holds a non-integer or huge extent");
        shape.push_back(extent);
        text = text.substr(static_cast<size_t>(result.ptr - text.data()));
    }
    return shape;
}

}  // namespace

std::string to_string(NpyDtype dtype) { return info(dtype).name; }
size_t npy_dtype_size(NpyDtype dtype) { return info(dtype).size; }

void write_npy_bytes(const std::filesystem::path& path, NpyDtype dtype, const void* data,
                     const std::vector<size_t>& shape, WriteMode mode) {
    const size_t bytes = checked_count(shape, info(dtype).size, path.string());
    if (bytes > 0 && !data) throw InputError(path.string(), "cannot write an array without data");
    std::string header = std::string("{'descr': '") + info(dtype).descr +
                         "', 'fortran_order': False, 'shape': " + shape_text(shape) + ", }";
    // Pad with spaces and end with a newline so that the data starts at a multiple of 64 bytes.
    const size_t prefix = kMagicSize + 2 + 2;
    header.append(63 - (prefix + header.size()) % 64, ' ');
    header += '\n';
    if (header.size() > 65535)
        throw InputError(path.string(), "array has too many dimensions for a version 1.0 header");

    write_file_atomically(path, mode, [&](std::ostream& out) {
        const uint16_t length = static_cast<uint16_t>(header.size());
        out.write(kMagic, kMagicSize);
        out.put(1).put(0);
        out.put(static_cast<char>(length & 0xff)).put(static_cast<char>(length >> 8));
        out << header;
        out.write(static_cast<const char*>(data), static_cast<std::streamsize>(bytes));
    });
}

NpyArray read_npy(const std::filesystem::path& path) {
    const std::string where = path.string();
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(where, std::filesystem::exists(path) ? "cannot be opened" : "no such file");
    const uint64_t file_size = std::filesystem::file_size(path);

    char preamble[12] = {};
    in.read(preamble, sizeof preamble);
    if (in.gcount() < 10 || std::string_view(preamble, kMagicSize) != std::string_view(kMagic, kMagicSize))
        throw InputError(where, "not a .npy file (bad magic: it does not start with \\x93NUMPY)");
    const int major = static_cast<unsigned char>(preamble[6]);
    if (major < 1 || major > 3)
        throw InputError(where, "unsupported .npy format version " + std::to_string(major) + "." +
                                    std::to_string(static_cast<unsigned char>(preamble[7])));
    // Version 1 has a 16-bit header length; versions 2 and 3 a 32-bit one.
    const size_t header_start = major == 1 ? 10 : 12;
    const uint64_t header_length = major == 1 ? detail::load_little_endian<uint16_t>(preamble + 8)
                                              : detail::load_little_endian<uint32_t>(preamble + 8);
    if (header_start + header_length > file_size)
        throw InputError(where, "truncated: the header claims " + std::to_string(header_length) +
                                    " bytes but the file has " + std::to_string(file_size) + " in all");
    std::string dict(header_length, '\0');
    in.clear();
    in.seekg(static_cast<std::streamoff>(header_start));
    in.read(dict.data(), static_cast<std::streamsize>(header_length));

    NpyArray array;
    array.path = path;
    array.dtype = parse_descr(dict, where);
    if (entry(dict, "fortran_order", where).starts_with("True"))
        throw InputError(where, "is in Fortran order; only C order is supported (save np.ascontiguousarray(a))");
    array.shape = parse_shape(dict, where);

    const size_t bytes = checked_count(array.shape, npy_dtype_size(array.dtype), where);
    const uint64_t available = file_size - header_start - header_length;
    if (bytes > available)
        throw InputError(where, "truncated: a " + to_string(array.dtype) + " array of shape " +
                                    shape_text(array.shape) + " needs " + std::to_string(bytes) +
                                    " bytes of data but the file has " + std::to_string(available));
    array.data.resize(bytes);
    if (!in.read(reinterpret_cast<char*>(array.data.data()), static_cast<std::streamsize>(bytes)))
        throw InputError(where, "reading " + std::to_string(bytes) + " bytes of data failed");
    return array;
}

}  // namespace vksplat::io
