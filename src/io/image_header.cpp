// Image sizes read from the file header (PNG's IHDR, JPEG's start-of-frame), without decoding the
// pixels: a NeRF camera file may name hundreds of images only to give their size, and decoding
// pulls in the image codecs, which a GPU host running the benchmark does not have.
#include <algorithm>
#include <array>
#include <cstdint>
#include <fstream>
#include <optional>
#include <string>

#include "vksplat/error.hpp"
#include "vksplat/io/image.hpp"

namespace vksplat::io {
namespace {

uint32_t big_endian(const unsigned char* bytes, int count) {
    uint32_t value = 0;
    for (int i = 0; i < count; ++i) value = (value << 8) | bytes[i];
    return value;
}

bool is_start_of_frame(int marker) {
    // SOF0..SOF15 except DHT (C4), JPG (C8) and DAC (CC), which share the range.
    return marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
}

std::array<int, 2> jpeg_size(std::ifstream& in, const std::string& where) {
    for (;;) {
        int byte = in.get();
        if (byte != 0xFF) throw InputError(where, "JPEG: expected a marker, the file is corrupt or truncated");
        while (byte == 0xFF) byte = in.get();  // fill bytes
        if (byte == EOF) break;
        const int marker = byte;
        if (marker == 0xD8 || marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) continue;  // no length
        if (marker == 0xD9 || marker == 0xDA) break;  // end of image or scan data before any frame header
        unsigned char length_bytes[2];
        if (!in.read(reinterpret_cast<char*>(length_bytes), 2)) break;
        const uint32_t length = big_endian(length_bytes, 2);
        if (length < 2) throw InputError(where, "JPEG: a segment length below 2");
        if (is_start_of_frame(marker)) {
            unsigned char header[5];  // precision, height, width
            if (!in.read(reinterpret_cast<char*>(header), 5)) break;
            return {int(big_endian(header + 3, 2)), int(big_endian(header + 1, 2))};
        }
        in.seekg(length - 2, std::ios::cur);
    }
    throw InputError(where, "JPEG: no frame header (the file is truncated or not a JPEG)");
}

}  // namespace

std::optional<std::array<int, 2>> header_image_size(const std::filesystem::path& path) {
    const std::string where = path.string();
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(where, "cannot open the image");
    unsigned char head[24] = {};
    in.read(reinterpret_cast<char*>(head), 2);
    std::array<int, 2> size{0, 0};
    if (in.gcount() == 2 && head[0] == 0xFF && head[1] == 0xD8) {
        size = jpeg_size(in, where);
    } else {
        static constexpr unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
        in.read(reinterpret_cast<char*>(head) + 2, 22);
        if (in.gcount() != 22 || !std::equal(kPng, kPng + 8, head) || std::string(head + 12, head + 16) != "IHDR")
            return std::nullopt;
        size = {int(big_endian(head + 16, 4)), int(big_endian(head + 20, 4))};
    }
    if (size[0] <= 0 || size[1] <= 0 || size[0] > 1 << 20 || size[1] > 1 << 20)
        throw InputError(where, "image header gives an impossible size " + std::to_string(size[0]) + "x" +
                                    std::to_string(size[1]));
    return size;
}

std::array<int, 2> read_image_size(const std::filesystem::path& path) {
    const auto size = header_image_size(path);
    if (!size)
        throw InputError(path.string(), "not a PNG or JPEG image (only their sizes can be read without decoding)");
    return *size;
}

}  // namespace vksplat::io
