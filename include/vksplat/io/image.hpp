#pragma once
// Photos and renders as float RGB in [0, 1], read and written through OpenCV.
#include <array>
#include <filesystem>
#include <optional>
#include <vector>

#include "vksplat/io/write_mode.hpp"

namespace vksplat::io {

struct ImageRGB {
    int width = 0;
    int height = 0;
    std::vector<float> rgb;  // row-major, 3 values (r, g, b) per pixel, in [0, 1]
};

// Reads an 8- or 16-bit grey, RGB or RGBA image (any format OpenCV decodes). An alpha channel is
// composited over `background` (straight alpha: colour * alpha + background * (1 - alpha)). EXIF
// orientation is ignored, as COLMAP and the 3DGS trainers ignore it. Throws InputError naming the
// file if it is missing, undecodable or of another pixel type.
ImageRGB read_image_rgb(const std::filesystem::path& path, const std::array<float, 3>& background);

// Width and height of a PNG or JPEG from its header, without decoding the pixels. Throws
// InputError naming the file for anything else, a truncated header or an impossible size.
std::array<int, 2> read_image_size(const std::filesystem::path& path);
// The same where the file is a PNG or JPEG (told by its content, not its name); nullopt for any
// other format, whose size only decoding tells.
std::optional<std::array<int, 2>> header_image_size(const std::filesystem::path& path);

// Writes a PNG of 8 or 16 bits per channel. Values are clamped to [0, 1] (NaN becomes 0) and
// rounded to the nearest level.
void write_png_rgb(const std::filesystem::path& path, int width, int height, const float* rgb, int bit_depth,
                   WriteMode mode = WriteMode::refuse_existing);

// Writes a 16-bit grey PNG, e.g. an alpha map; values as for write_png_rgb.
void write_png_gray16(const std::filesystem::path& path, int width, int height, const float* values,
                      WriteMode mode = WriteMode::refuse_existing);

}  // namespace vksplat::io
