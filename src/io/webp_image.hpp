#pragma once
// RGBA images as lossless WebP, through libwebp: the textures of a SOG scene. Lossless and exact,
// so every byte of every channel comes back as it was written, under zero alpha too (libwebp's
// simple lossless encoder rewrites the colour of fully transparent pixels, and OpenCV's WebP writer
// uses it: a SOG's sh0 texture keeps its colour indices under an opacity of 0).
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace vksplat::io::detail {

struct RgbaImage {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgba;  // width * height * 4 bytes, row by row
};

// The image as a lossless WebP file. Throws InputError naming `where` if libwebp refuses it
// (a side over 16383 pixels, or out of memory).
std::string encode_lossless_webp(const RgbaImage& image, const std::string& where);
// Any WebP file (lossless or lossy, with or without alpha) as RGBA. Throws InputError naming
// `where` if the bytes are not a WebP image libwebp can decode.
RgbaImage decode_webp(std::string_view bytes, const std::string& where);

}  // namespace vksplat::io::detail
