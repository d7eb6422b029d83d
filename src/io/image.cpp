// Images through OpenCV, which stores channels as BGR(A): the conversions to and from RGB live here.
#include "vksplat/io/image.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "vksplat/error.hpp"

namespace vksplat::io {
namespace {

// One [0, 1] value as an integer level of `max_level`, clamped and rounded to nearest.
template <typename Level>
Level quantise(float value, float max_level) {
    if (!(value > 0.0f)) return 0;  // also NaN
    return static_cast<Level>(std::lround(std::min(value, 1.0f) * max_level));
}

// Encodes `image` as PNG and writes it atomically.
void write_png(const std::filesystem::path& path, const cv::Mat& image, WriteMode mode) {
    std::vector<uchar> bytes;
    if (!cv::imencode(".png", image, bytes)) throw InputError(path.string(), "PNG encoding failed");
    write_file_atomically(path, mode, [&](std::ostream& out) {
        out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    });
}

void check_size(const std::filesystem::path& path, int width, int height, const float* values) {
    if (width <= 0 || height <= 0)
        throw InputError(path.string(), "cannot write an image of " + std::to_string(width) + "x" +
                                            std::to_string(height) + " pixels");
    if (!values) throw InputError(path.string(), "cannot write an image without pixel values");
}

template <typename Level>
cv::Mat quantised_bgr(int width, int height, const float* rgb, float max_level) {
    cv::Mat image(height, width, CV_MAKETYPE(cv::DataType<Level>::depth, 3));
    for (int y = 0; y < height; ++y) {
        Level* row = image.ptr<Level>(y);
        const float* source = rgb + static_cast<size_t>(y) * width * 3;
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c) row[x * 3 + c] = quantise<Level>(source[x * 3 + 2 - c], max_level);
    }
    return image;
}

}  // namespace

ImageRGB read_image_rgb(const std::filesystem::path& path, const std::array<float, 3>& background) {
    const std::string where = path.string();
    if (!std::filesystem::is_regular_file(path)) throw InputError(where, "no such file");
    // IMREAD_UNCHANGED keeps 16 bits and alpha, and leaves EXIF orientation alone.
    const cv::Mat raw = cv::imread(where, cv::IMREAD_UNCHANGED);
    if (raw.empty()) throw InputError(where, "cannot be decoded as an image");
    double scale = 0;
    if (raw.depth() == CV_8U)
        scale = 1.0 / 255.0;
    else if (raw.depth() == CV_16U)
        scale = 1.0 / 65535.0;
    else
        throw InputError(where, "has " + std::to_string(raw.elemSize1() * 8) + "-bit samples of OpenCV depth " +
                                    std::to_string(raw.depth()) + "; only 8- and 16-bit integer images are read");
    const int channels = raw.channels();
    if (channels != 1 && channels != 3 && channels != 4)
        throw InputError(where,
                         "has " + std::to_string(channels) + " channels; expected 1 (grey), 3 (RGB) or 4 (RGBA)");

    cv::Mat values;
    raw.convertTo(values, CV_32F, scale);
    ImageRGB image{raw.cols, raw.rows, std::vector<float>(static_cast<size_t>(raw.cols) * raw.rows * 3)};
    for (int y = 0; y < image.height; ++y) {
        const float* row = values.ptr<float>(y);
        float* out = image.rgb.data() + static_cast<size_t>(y) * image.width * 3;
        for (int x = 0; x < image.width; ++x, row += channels, out += 3) {
            if (channels == 1) {
                out[0] = out[1] = out[2] = row[0];
                continue;
            }
            const float alpha = channels == 4 ? row[3] : 1.0f;
            for (int c = 0; c < 3; ++c)
                out[c] = row[2 - c] * alpha + background[static_cast<size_t>(c)] * (1.0f - alpha);
        }
    }
    return image;
}

void write_png_rgb(const std::filesystem::path& path, int width, int height, const float* rgb, int bit_depth,
                   WriteMode mode) {
    check_size(path, width, height, rgb);
    if (bit_depth == 8)
        write_png(path, quantised_bgr<uint8_t>(width, height, rgb, 255.0f), mode);
    else if (bit_depth == 16)
        write_png(path, quantised_bgr<uint16_t>(width, height, rgb, 65535.0f), mode);
    else
        throw InputError(path.string(), "PNG bit depth must be 8 or 16, not " + std::to_string(bit_depth));
}

void write_png_gray16(const std::filesystem::path& path, int width, int height, const float* values, WriteMode mode) {
    check_size(path, width, height, values);
    cv::Mat image(height, width, CV_16UC1);
    for (int y = 0; y < height; ++y) {
        uint16_t* row = image.ptr<uint16_t>(y);
        for (int x = 0; x < width; ++x)
            row[x] = quantise<uint16_t>(values[static_cast<size_t>(y) * width + x], 65535.0f);
    }
    write_png(path, image, mode);
}

}  // namespace vksplat::io
