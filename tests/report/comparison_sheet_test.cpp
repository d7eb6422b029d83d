// Comparison sheets: layout, pixel values, captions, the heat map panel and its colour bar.
#include "vksplat/report/comparison_sheet.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "vksplat/error.hpp"
#include "vksplat/eval/metrics.hpp"

namespace vksplat::report {
namespace {

using Rgb = std::array<float, 3>;

SheetPanel solid(std::string caption, int w, int h, Rgb colour) {
    SheetPanel p{std::move(caption), w, h, {}};
    for (int i = 0; i < w * h; ++i) p.rgb.insert(p.rgb.end(), colour.begin(), colour.end());
    return p;
}

Rgb pixel(const io::ImageRGB& image, int x, int y) {
    const size_t i = (static_cast<size_t>(y) * image.width + x) * 3;
    return {image.rgb[i], image.rgb[i + 1], image.rgb[i + 2]};
}

Rgb pixel(const SheetPanel& panel, int x, int y) {
    const size_t i = (static_cast<size_t>(y) * panel.width + x) * 3;
    return {panel.rgb[i], panel.rgb[i + 1], panel.rgb[i + 2]};
}

Rgb byte_colour(int r, int g, int b) { return {r / 255.0f, g / 255.0f, b / 255.0f}; }

const Rgb kWhite = {1.0f, 1.0f, 1.0f};

// Pixels darker than mid-grey in a rectangle: text.
int dark_pixels(const io::ImageRGB& image, int x0, int y0, int x1, int y1) {
    int n = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            const Rgb p = pixel(image, x, y);
            if (p[0] + p[1] + p[2] < 1.5f) ++n;
        }
    return n;
}

TEST(ComparisonSheet, PutsPanelsSideBySideUnderACaptionStrip) {
    const Rgb red = {1, 0, 0}, blue = {0, 0.5f, 1};
    const std::vector<SheetPanel> panels = {solid("photo", 30, 20, red), solid("render", 40, 25, blue)};
    const io::ImageRGB sheet = compose_comparison_sheet(panels);
    const int strip = caption_strip_height(panels);
    EXPECT_EQ(strip, 24);
    EXPECT_EQ(sheet.width, 30 + 40);
    EXPECT_EQ(sheet.height, strip + 25);
    ASSERT_EQ(sheet.rgb.size(), static_cast<size_t>(sheet.width) * sheet.height * 3);
    // Pictures below the strip, at their places, quantised to 8 bits.
    EXPECT_EQ(pixel(sheet, 0, strip), red);
    EXPECT_EQ(pixel(sheet, 29, strip + 19), red);
    EXPECT_EQ(pixel(sheet, 30, strip), byte_colour(0, 128, 255));
    EXPECT_EQ(pixel(sheet, 69, strip + 24), byte_colour(0, 128, 255));
    // The shorter panel leaves white under it.
    EXPECT_EQ(pixel(sheet, 10, strip + 20), kWhite);
    EXPECT_EQ(pixel(sheet, 29, strip + 24), kWhite);
    // Captions: dark text inside each panel's strip, white at the corners.
    EXPECT_GT(dark_pixels(sheet, 0, 0, 30, strip), 10);
    EXPECT_GT(dark_pixels(sheet, 30, 0, 70, strip), 10);
    EXPECT_EQ(pixel(sheet, 0, 0), kWhite);
    EXPECT_EQ(pixel(sheet, 69, 0), kWhite);
}

TEST(ComparisonSheet, KeepsEachCaptionOverItsOwnPanel) {
    const std::vector<SheetPanel> panels = {
        solid("a very long caption that cannot possibly fit in thirty pixels", 30, 20, {0, 0, 0}),
        solid("", 50, 20, {0, 0, 0}), solid("\xCE\x94 PSNR \xE2\x89\xA5 30 (non-ASCII)", 60, 20, {0, 0, 0})};
    const io::ImageRGB sheet = compose_comparison_sheet(panels);
    const int strip = caption_strip_height(panels);
    EXPECT_GT(dark_pixels(sheet, 0, 0, 30, strip), 5);
    EXPECT_EQ(dark_pixels(sheet, 30, 0, 80, strip), 0);  // no caption, and nothing spilt from the left
    EXPECT_GT(dark_pixels(sheet, 80, 0, 140, strip), 5);
}

TEST(ComparisonSheet, ClampsValuesAndShowsNanAsBlack) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    SheetPanel p{"", 3, 1, {2.0f, -1.0f, 0.5f, nan, nan, nan, 1.0f, 0.0f, 0.25f}};
    const io::ImageRGB sheet = compose_comparison_sheet({p});
    const int strip = caption_strip_height({p});
    EXPECT_EQ(pixel(sheet, 0, strip), byte_colour(255, 0, 128));
    EXPECT_EQ(pixel(sheet, 1, strip), byte_colour(0, 0, 0));
    EXPECT_EQ(pixel(sheet, 2, strip), byte_colour(255, 0, 64));
}

TEST(ComparisonSheet, GrowsTheCaptionStripWithThePictures) {
    EXPECT_EQ(caption_strip_height({solid("", 4, 400, {0, 0, 0})}), 24);
    EXPECT_EQ(caption_strip_height({solid("", 4, 1000, {0, 0, 0})}), 60);
    EXPECT_EQ(caption_strip_height({solid("", 4, 5000, {0, 0, 0})}), 64);
}

TEST(ComparisonSheet, RejectsBadPanels) {
    EXPECT_THROW(compose_comparison_sheet({}), std::invalid_argument);
    SheetPanel short_rgb = solid("x", 4, 4, {0, 0, 0});
    short_rgb.rgb.pop_back();
    EXPECT_THROW(compose_comparison_sheet({solid("ok", 4, 4, {0, 0, 0}), short_rgb}), std::invalid_argument);
    EXPECT_THROW(compose_comparison_sheet({SheetPanel{"empty", 0, 4, {}}}), std::invalid_argument);
}

TEST(HeatMapPanel, IsTheColouredErrorMapFollowedByALabelledColourBar) {
    const int w = 100, h = 80;
    const float max_error = 0.2f;
    std::vector<float> a(static_cast<size_t>(w) * h * 3, 0.5f), b = a;
    // Error 0 on the left half, max_error / 2 in the top right, 2 * max_error (saturating) below it.
    for (int y = 0; y < h; ++y)
        for (int x = w / 2; x < w; ++x)
            for (int c = 0; c < 3; ++c) b[(static_cast<size_t>(y) * w + x) * 3 + c] += y < h / 2 ? 0.1f : 0.4f;
    const SheetPanel panel = heat_map_panel(a.data(), b.data(), w, h, max_error, "error");
    EXPECT_EQ(panel.caption, "error");
    EXPECT_EQ(panel.height, h);
    EXPECT_EQ(panel.width, w + heat_bar_width(h, max_error));
    EXPECT_GE(heat_bar_width(h, max_error), 30);
    ASSERT_EQ(panel.rgb.size(), static_cast<size_t>(panel.width) * h * 3);

    // The map: exactly colorize_heat of error_map.
    std::vector<uint8_t> expected;
    eval::colorize_heat(eval::error_map(a.data(), b.data(), w, h), max_error, expected);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const uint8_t* e = expected.data() + (static_cast<size_t>(y) * w + x) * 3;
            ASSERT_EQ(pixel(panel, x, y), byte_colour(e[0], e[1], e[2])) << x << "," << y;
        }
    std::vector<uint8_t> ends;
    eval::colorize_heat({0.0f, max_error}, max_error, ends);
    const Rgb zero = byte_colour(ends[0], ends[1], ends[2]), top = byte_colour(ends[3], ends[4], ends[5]);
    EXPECT_EQ(pixel(panel, 0, 0), zero);
    EXPECT_EQ(pixel(panel, w - 1, h - 1), top);

    // The bar: somewhere in its upper rows the top colour, in its lower rows the colour of 0, and
    // dark label text to the right of the gradient.
    auto find = [&](const Rgb& colour, int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = w; x < panel.width; ++x)
                if (pixel(panel, x, y) == colour) return true;
        return false;
    };
    EXPECT_TRUE(find(top, 0, h / 3));
    EXPECT_FALSE(find(top, h / 2, h));
    EXPECT_TRUE(find(zero, 2 * h / 3, h));
    EXPECT_FALSE(find(zero, 0, h / 2));
    int dark_right = 0;
    for (int y = 0; y < h; ++y)
        for (int x = w + 30; x < panel.width; ++x) {
            const Rgb p = pixel(panel, x, y);
            if (p[0] + p[1] + p[2] < 1.5f && p[0] == p[1] && p[1] == p[2]) ++dark_right;
        }
    EXPECT_GT(dark_right, 20);
    // The bar's background is white.
    EXPECT_EQ(pixel(panel, w + 1, 0), kWhite);
    EXPECT_EQ(pixel(panel, panel.width - 1, h - 1), kWhite);
}

TEST(HeatMapPanel, WorksForTinyMapsAndRejectsBadInput) {
    const std::vector<float> a(2 * 2 * 3, 0.0f), b(2 * 2 * 3, 1.0f);
    const SheetPanel tiny = heat_map_panel(a.data(), b.data(), 2, 2, 1.0f, "tiny");
    EXPECT_EQ(tiny.width, 2 + heat_bar_width(2, 1.0f));
    EXPECT_EQ(tiny.rgb.size(), static_cast<size_t>(tiny.width) * 2 * 3);
    EXPECT_THROW(heat_map_panel(a.data(), b.data(), 2, 2, 0.0f, ""), std::invalid_argument);
    EXPECT_THROW(heat_map_panel(nullptr, b.data(), 2, 2, 1.0f, ""), std::invalid_argument);
    EXPECT_THROW(heat_map_panel(a.data(), b.data(), 0, 2, 1.0f, ""), std::invalid_argument);
}

TEST(WriteComparisonSheet, WritesThePngAndRefusesToReplaceItUnlessAsked) {
    const auto dir = std::filesystem::temp_directory_path() / ("vksplat_sheet_test_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const auto png = dir / "sheet.png";
    std::vector<float> a(64 * 48 * 3), b(a.size());
    for (size_t i = 0; i < a.size(); ++i) {
        a[i] = static_cast<float>(i % 251) / 250.0f;
        b[i] = static_cast<float>(i % 241) / 240.0f;
    }
    const std::vector<SheetPanel> panels = {{"photo", 64, 48, a}, {"render", 64, 48, b},
                                            heat_map_panel(a.data(), b.data(), 64, 48, 0.5f, "error")};
    write_comparison_sheet(png, panels, io::WriteMode::refuse_existing);
    const io::ImageRGB read = io::read_image_rgb(png, {0, 0, 0});
    const io::ImageRGB composed = compose_comparison_sheet(panels);
    EXPECT_EQ(read.width, 64 + 64 + 64 + heat_bar_width(48, 0.5f));
    EXPECT_EQ(read.width, composed.width);
    EXPECT_EQ(read.height, composed.height);
    ASSERT_EQ(read.rgb.size(), composed.rgb.size());
    for (size_t i = 0; i < read.rgb.size(); ++i)  // the same 8-bit levels, divided by 255 either way
        ASSERT_NEAR(read.rgb[i], composed.rgb[i], 1e-6f) << i;
    EXPECT_THROW(write_comparison_sheet(png, panels, io::WriteMode::refuse_existing), InputError);
    EXPECT_NO_THROW(write_comparison_sheet(png, {panels[0]}, io::WriteMode::overwrite));
    EXPECT_EQ(io::read_image_rgb(png, {0, 0, 0}).width, 64);
    std::filesystem::remove_all(dir);
}

// JPEG by the name, a tenth of the PNG's weight for a picture like a render, decoded close to what
// was composed; any other extension is refused before anything is written.
TEST(WriteComparisonSheet, WritesJpegWhenTheNameSaysSo) {
    const auto dir = std::filesystem::temp_directory_path() / ("vksplat_sheet_jpeg_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    // A smooth picture with noise, as renders of a scene are.
    const int w = 256, h = 192;
    std::vector<float> render(static_cast<size_t>(w) * h * 3);
    uint32_t state = 1;
    for (size_t i = 0; i < render.size(); ++i) {
        state = state * 1664525u + 1013904223u;
        const size_t p = i / 3;
        render[i] = 0.5f + 0.3f * std::sin(float(p % w) * 0.05f + float(i % 3)) * std::cos(float(p / w) * 0.04f) +
                    0.02f * float(state >> 24) / 255.0f;
    }
    const std::vector<SheetPanel> panels = {{"photo", w, h, render}, {"render", w, h, render}};
    write_comparison_sheet(dir / "sheet.jpg", panels, io::WriteMode::refuse_existing);
    write_comparison_sheet(dir / "sheet.JPEG", panels, io::WriteMode::refuse_existing);
    write_comparison_sheet(dir / "sheet.png", panels, io::WriteMode::refuse_existing);
    std::ifstream jpeg(dir / "sheet.jpg", std::ios::binary);
    EXPECT_EQ(jpeg.get(), 0xFF);
    EXPECT_EQ(jpeg.get(), 0xD8);
    EXPECT_LT(std::filesystem::file_size(dir / "sheet.jpg"), std::filesystem::file_size(dir / "sheet.png") / 4);
    const io::ImageRGB read = io::read_image_rgb(dir / "sheet.jpg", {0, 0, 0});
    const io::ImageRGB composed = compose_comparison_sheet(panels);
    ASSERT_EQ(read.rgb.size(), composed.rgb.size());
    const int strip = caption_strip_height(panels);
    double error = 0;
    for (size_t i = static_cast<size_t>(strip + 8) * read.width * 3; i < read.rgb.size(); ++i)
        error += std::abs(read.rgb[i] - composed.rgb[i]);
    EXPECT_LT(error / double(read.rgb.size()), 0.02) << "mean error of the pictures";
    EXPECT_THROW(write_comparison_sheet(dir / "sheet.bmp", panels, io::WriteMode::overwrite), InputError);
    EXPECT_FALSE(std::filesystem::exists(dir / "sheet.bmp"));
    std::filesystem::remove_all(dir);
}

TEST(ErrorWindow, FindsWhereTwoPicturesDifferMost) {
    const int w = 64, h = 48;
    std::vector<float> a(static_cast<size_t>(w) * h * 3, 0.5f), b = a;
    for (int y = 30; y < 36; ++y)  // a 6 x 6 patch far off, and a fainter one elsewhere
        for (int x = 40; x < 46; ++x)
            for (int c = 0; c < 3; ++c) b[(static_cast<size_t>(y) * w + x) * 3 + c] = 1.0f;
    for (int c = 0; c < 3; ++c) b[(static_cast<size_t>(5) * w + 5) * 3 + c] = 0.6f;
    const ErrorWindow window = largest_error_window(a.data(), b.data(), w, h, 8);
    EXPECT_EQ(window.size, 8);
    EXPECT_LE(window.x, 40);
    EXPECT_GE(window.x + 8, 46);
    EXPECT_LE(window.y, 30);
    EXPECT_GE(window.y + 8, 36);
    EXPECT_NEAR(window.mean_error, 36 * 0.5 / 64, 1e-6);
    EXPECT_EQ(largest_error_window(a.data(), b.data(), w, h, 100).size, h) << "at most the image";
    EXPECT_EQ(largest_error_window(a.data(), a.data(), w, h, 8).mean_error, 0.0);
    EXPECT_THROW(largest_error_window(a.data(), b.data(), w, h, 0), std::invalid_argument);
}

TEST(ErrorWindow, ZoomsBothPicturesOfTheWindowAndOutlinesIt) {
    const int w = 40, h = 30;
    const std::vector<float> a = solid("a", w, h, {1, 0, 0}).rgb, b = solid("b", w, h, {0, 0, 1}).rgb;
    const ErrorWindow window{10, 5, 6, 0.0};
    const SheetPanel zoom = zoomed_window_panel(a.data(), b.data(), w, h, window, "zoom");
    EXPECT_EQ(zoom.width, h / 2);
    EXPECT_EQ(zoom.height, h);
    EXPECT_EQ(pixel(zoom, 3, 2), (Rgb{1, 0, 0})) << "a above";
    EXPECT_EQ(pixel(zoom, 3, h - 2), (Rgb{0, 0, 1})) << "b below";
    EXPECT_EQ(pixel(zoom, 3, h / 2), kWhite) << "a white line between";
    EXPECT_THROW(zoomed_window_panel(a.data(), b.data(), w, h, {36, 5, 6, 0.0}, ""), std::invalid_argument);

    SheetPanel panel = solid("p", w, h, {0, 0, 0});
    outline_window(panel, window, {0, 1, 1});
    EXPECT_EQ(pixel(panel, 10, 5), (Rgb{0, 1, 1}));
    EXPECT_EQ(pixel(panel, 15, 10), (Rgb{0, 1, 1}));
    EXPECT_EQ(pixel(panel, 13, 8), (Rgb{0, 0, 0})) << "inside stays";
    EXPECT_EQ(pixel(panel, 9, 5), (Rgb{0, 0, 0})) << "outside stays";
}

}  // namespace
}  // namespace vksplat::report
