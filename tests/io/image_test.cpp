// PNG writing and reading: 8 and 16 bits, grey, and RGBA composited over a background.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include <opencv2/imgcodecs.hpp>

#include "io/io_test_helpers.hpp"
#include "vksplat/io/image.hpp"

namespace vksplat::io::test {
namespace {

std::vector<float> ramp(int width, int height, int channels) {
    std::vector<float> values(static_cast<size_t>(width) * height * channels);
    for (size_t i = 0; i < values.size(); ++i) values[i] = static_cast<float>((i * 37) % 101) / 100.0f;
    return values;
}

TEST(Image, Rgb8RoundTripsToTheNearestLevel) {
    ScratchDir dir;
    const int width = 7, height = 5;
    std::vector<float> rgb = ramp(width, height, 3);
    rgb[0] = -0.5f;  // clamped to 0
    rgb[1] = 2.0f;   // clamped to 1
    rgb[2] = std::nanf("");
    write_png_rgb(dir / "a.png", width, height, rgb.data(), 8);
    const ImageRGB image = read_image_rgb(dir / "a.png", {0, 0, 0});
    ASSERT_EQ(image.width, width);
    ASSERT_EQ(image.height, height);
    ASSERT_EQ(image.rgb.size(), rgb.size());
    EXPECT_EQ(image.rgb[0], 0.0f);
    EXPECT_EQ(image.rgb[1], 1.0f);
    EXPECT_EQ(image.rgb[2], 0.0f);
    for (size_t i = 3; i < rgb.size(); ++i)
        EXPECT_FLOAT_EQ(image.rgb[i], std::round(rgb[i] * 255.0f) / 255.0f) << "value " << i;
}

TEST(Image, Rgb16KeepsSixteenBits) {
    ScratchDir dir;
    const int width = 4, height = 3;
    const std::vector<float> rgb = ramp(width, height, 3);
    write_png_rgb(dir / "b.png", width, height, rgb.data(), 16);
    const ImageRGB image = read_image_rgb(dir / "b.png", {0, 0, 0});
    for (size_t i = 0; i < rgb.size(); ++i) EXPECT_NEAR(image.rgb[i], rgb[i], 0.5 / 65535 + 1e-7) << "value " << i;
}

TEST(Image, Gray16IsReadAsGreyRgb) {
    ScratchDir dir;
    const int width = 3, height = 2;
    const std::vector<float> alpha = {0, 0.25f, 0.5f, 0.75f, 1, 0.1f};
    write_png_gray16(dir / "alpha.png", width, height, alpha.data());
    const ImageRGB image = read_image_rgb(dir / "alpha.png", {0, 0, 0});
    for (size_t i = 0; i < alpha.size(); ++i)
        for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(image.rgb[i * 3 + c], alpha[i], 0.5 / 65535 + 1e-7);
}

// A minimal PNG encoder (stored, uncompressed deflate) for an RGBA file, which our writers never make.
uint32_t crc32(const std::string& bytes) {
    uint32_t crc = 0xffffffffu;
    for (unsigned char byte : bytes) {
        crc ^= byte;
        for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
    return crc ^ 0xffffffffu;
}

std::string big_endian32(uint32_t value) {
    return {static_cast<char>(value >> 24), static_cast<char>(value >> 16), static_cast<char>(value >> 8),
            static_cast<char>(value)};
}

std::string chunk(const std::string& type, const std::string& data) {
    return big_endian32(static_cast<uint32_t>(data.size())) + type + data + big_endian32(crc32(type + data));
}

std::string rgba8_png(int width, int height, const std::vector<uint8_t>& rgba) {
    std::string raw;
    for (int y = 0; y < height; ++y) {
        raw += '\0';  // filter: none
        raw.append(reinterpret_cast<const char*>(rgba.data()) + static_cast<size_t>(y) * width * 4,
                   static_cast<size_t>(width) * 4);
    }
    uint32_t a = 1, b = 0;
    for (unsigned char byte : raw) {
        a = (a + byte) % 65521;
        b = (b + a) % 65521;
    }
    std::string zlib = "\x78\x01";
    zlib += '\x01';  // one final stored block
    const auto length = static_cast<uint16_t>(raw.size());
    zlib += {static_cast<char>(length & 0xff), static_cast<char>(length >> 8), static_cast<char>(~length & 0xff),
             static_cast<char>((~length >> 8) & 0xff)};
    zlib += raw + big_endian32((b << 16) | a);
    const std::string header = big_endian32(static_cast<uint32_t>(width)) +
                               big_endian32(static_cast<uint32_t>(height)) + std::string("\x08\x06\x00\x00\x00", 5);
    return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", header) + chunk("IDAT", zlib) + chunk("IEND", "");
}

TEST(Image, RgbaIsCompositedOverTheBackground) {
    ScratchDir dir;
    // Opaque red, transparent, half-transparent white.
    write_bytes(dir / "rgba.png", rgba8_png(3, 1, {255, 0, 0, 255, 10, 20, 30, 0, 255, 255, 255, 128}));
    const ImageRGB image = read_image_rgb(dir / "rgba.png", {0.0f, 0.5f, 1.0f});
    ASSERT_EQ(image.width, 3);
    const float half = 128.0f / 255.0f;
    const std::vector<float> expected = {1, 0, 0, 0, 0.5f, 1, half, half + 0.5f * (1 - half), 1};
    for (size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(image.rgb[i], expected[i], 1e-6) << "value " << i;
}

TEST(Image, Errors) {
    ScratchDir dir;
    expect_input_error([&] { read_image_rgb(dir / "none.png", {0, 0, 0}); }, {"none.png", "no such file"});
    write_bytes(dir / "junk.png", "not an image");
    expect_input_error([&] { read_image_rgb(dir / "junk.png", {0, 0, 0}); }, {"junk.png", "cannot be decoded"});

    const std::vector<float> rgb(12, 0.5f);
    expect_input_error([&] { write_png_rgb(dir / "c.png", 2, 2, rgb.data(), 12); }, {"c.png", "8 or 16"});
    write_png_rgb(dir / "c.png", 2, 2, rgb.data(), 8);
    expect_input_error([&] { write_png_rgb(dir / "c.png", 2, 2, rgb.data(), 8); }, {"c.png", "already exists"});
    EXPECT_NO_THROW(write_png_rgb(dir / "c.png", 2, 2, rgb.data(), 8, WriteMode::overwrite));
}

TEST(ImageSize, ReadFromPngAndJpegHeaders) {
    ScratchDir dir;
    const std::vector<float> rgb = ramp(13, 7, 3);
    write_png_rgb(dir / "a.png", 13, 7, rgb.data(), 16);
    EXPECT_EQ(read_image_size(dir / "a.png"), (std::array<int, 2>{13, 7}));
    // JPEGs from libjpeg through OpenCV: baseline and progressive (a different frame marker).
    const cv::Mat pixels(301, 517, CV_8UC3, cv::Scalar(10, 200, 30));
    ASSERT_TRUE(cv::imwrite((dir / "b.jpg").string(), pixels));
    EXPECT_EQ(read_image_size(dir / "b.jpg"), (std::array<int, 2>{517, 301}));
    ASSERT_TRUE(cv::imwrite((dir / "c.jpg").string(), pixels, {cv::IMWRITE_JPEG_PROGRESSIVE, 1}));
    EXPECT_EQ(read_image_size(dir / "c.jpg"), (std::array<int, 2>{517, 301}));
}

// Told by content, not by name; other formats have no size short of decoding.
TEST(ImageSize, FromTheHeaderWhereThereIsOne) {
    ScratchDir dir;
    const std::vector<float> rgb = ramp(13, 7, 3);
    write_png_rgb(dir / "png_named.jpg", 13, 7, rgb.data(), 8);
    EXPECT_EQ(header_image_size(dir / "png_named.jpg"), (std::array<int, 2>{13, 7}));
    const cv::Mat pixels(9, 11, CV_8UC3, cv::Scalar(10, 200, 30));
    ASSERT_TRUE(cv::imwrite((dir / "c.bmp").string(), pixels));
    EXPECT_FALSE(header_image_size(dir / "c.bmp").has_value());
}

TEST(ImageSize, Errors) {
    ScratchDir dir;
    expect_input_error([&] { read_image_size(dir / "none.png"); }, {"none.png", "cannot open"});
    write_bytes(dir / "junk.png", "not an image at all, but long enough");
    expect_input_error([&] { read_image_size(dir / "junk.png"); }, {"junk.png", "not a PNG or JPEG"});
    write_bytes(dir / "short.png", std::string("\x89PNG\r\n\x1a\n", 8));
    expect_input_error([&] { read_image_size(dir / "short.png"); }, {"short.png", "not a PNG or JPEG"});
    // A JPEG cut before its frame header.
    const cv::Mat pixels(20, 30, CV_8UC3, cv::Scalar(1, 2, 3));
    std::vector<unsigned char> jpeg;
    ASSERT_TRUE(cv::imencode(".jpg", pixels, jpeg));
    write_bytes(dir / "cut.jpg", std::string(jpeg.begin(), jpeg.begin() + 4));
    expect_input_error([&] { read_image_size(dir / "cut.jpg"); }, {"cut.jpg", "JPEG"});
}

}  // namespace
}  // namespace vksplat::io::test
