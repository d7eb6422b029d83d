#include "vksplat/report/comparison_sheet.hpp"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "vksplat/error.hpp"
#include "vksplat/eval/metrics.hpp"

namespace vksplat::report {
namespace {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
const cv::Scalar kWhite(255, 255, 255);
const cv::Scalar kText(34, 34, 34);  // grey, so the same in RGB and BGR order
const cv::Scalar kOutline(120, 120, 120);

uint8_t to_byte(float v) {
    if (std::isnan(v)) return 0;
    return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

void check_panel(const SheetPanel& p, size_t index) {
    if (p.width <= 0 || p.height <= 0)
        throw std::invalid_argument("comparison sheet: panel " + std::to_string(index) + " ('" + p.caption +
                                    "') size " + std::to_string(p.width) + " x " + std::to_string(p.height) +
                                    " is not positive");
    const size_t expected = static_cast<size_t>(p.width) * static_cast<size_t>(p.height) * 3;
    if (p.rgb.size() != expected)
        throw std::invalid_argument("comparison sheet: panel " + std::to_string(index) + " ('" + p.caption +
                                    "') holds " + std::to_string(p.rgb.size()) + " values, not " +
                                    std::to_string(expected) + " for " + std::to_string(p.width) + " x " +
                                    std::to_string(p.height) + " RGB");
}

// Hershey fonts draw ASCII only: each other UTF-8 sequence becomes one '?'.
std::string printable_ascii(const std::string& text) {
    std::string out;
    for (size_t i = 0; i < text.size(); ++i) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (c < 0x80) out += (c >= 0x20 && c < 0x7F) ? static_cast<char>(c) : ' ';
        else if ((c & 0xC0) != 0x80) out += '?';
    }
    return out;
}

cv::Size text_size(const std::string& text, double scale, int thickness, int* baseline = nullptr) {
    int b = 0;
    const cv::Size s = cv::getTextSize(text, kFont, scale, thickness, &b);
    if (baseline) *baseline = b;
    return s;
}

// Up to 3 significant digits, without trailing zeros: 0.25 -> "0.25", 0.125 -> "0.125".
std::string short_number(double v) {
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof(buf), v, std::chars_format::general, 3);
    return std::string(buf, r.ptr);
}

struct BarLayout {
    double scale;
    int thickness;
    int text_height;
    std::array<std::string, 3> labels;  // 0, max/2, max
    int label_width;
    int gradient_x, gradient_width, width;
};

BarLayout bar_layout(int h, float max_error) {
    BarLayout b{};
    b.scale = std::clamp(h / 700.0, 0.35, 0.7);
    b.thickness = 1;
    b.labels = {short_number(0.0), short_number(max_error / 2.0), short_number(max_error)};
    b.label_width = 0;
    for (const std::string& l : b.labels) {
        const cv::Size s = text_size(l, b.scale, b.thickness);
        b.label_width = std::max(b.label_width, s.width);
        b.text_height = std::max(b.text_height, s.height);
    }
    b.gradient_x = 8;
    b.gradient_width = std::clamp(h / 40, 10, 24);
    b.width = b.gradient_x + b.gradient_width + 4 + 4 + b.label_width + 8;
    return b;
}

}  // namespace

int caption_strip_height(const std::vector<SheetPanel>& panels) {
    int tallest = 0;
    for (const SheetPanel& p : panels) tallest = std::max(tallest, p.height);
    return std::clamp(static_cast<int>(std::lround(tallest * 0.06)), 24, 64);
}

io::ImageRGB compose_comparison_sheet(const std::vector<SheetPanel>& panels) {
    if (panels.empty()) throw std::invalid_argument("comparison sheet: no panels");
    int width = 0, tallest = 0;
    for (size_t i = 0; i < panels.size(); ++i) {
        check_panel(panels[i], i);
        width += panels[i].width;
        tallest = std::max(tallest, panels[i].height);
    }
    const int strip = caption_strip_height(panels);
    cv::Mat canvas(strip + tallest, width, CV_8UC3, kWhite);  // channels in R, G, B order

    const double base_scale = strip * 0.5 / 22.0;  // caps of FONT_HERSHEY_SIMPLEX at scale 1 are ~22 px
    const int thickness = base_scale >= 0.75 ? 2 : 1;
    int x0 = 0;
    for (const SheetPanel& p : panels) {
        for (int y = 0; y < p.height; ++y) {
            auto* row = canvas.ptr<uint8_t>(strip + y) + static_cast<size_t>(x0) * 3;
            const float* src = p.rgb.data() + static_cast<size_t>(y) * p.width * 3;
            for (int i = 0; i < p.width * 3; ++i) row[i] = to_byte(src[i]);
        }
        // The caption: shrink to fit, then cut.
        std::string text = printable_ascii(p.caption);
        const int room = std::max(p.width - 8, 1);
        double scale = base_scale;
        if (!text.empty()) {
            const int w = text_size(text, scale, thickness).width;
            if (w > room) scale = std::max(scale * room / w, 0.35);
            if (text_size(text, scale, thickness).width > room) {
                while (!text.empty() && text_size(text + "..", scale, thickness).width > room) text.pop_back();
                text += "..";
            }
            int baseline = 0;
            const cv::Size s = text_size(text, scale, thickness, &baseline);
            const cv::Mat column = canvas(cv::Rect(x0, 0, p.width, strip));
            cv::putText(column, text, cv::Point((p.width - s.width) / 2, (strip + s.height) / 2), kFont, scale, kText,
                        thickness, cv::LINE_AA);
        }
        x0 += p.width;
    }

    io::ImageRGB out;
    out.width = canvas.cols;
    out.height = canvas.rows;
    out.rgb.resize(static_cast<size_t>(out.width) * out.height * 3);
    for (int y = 0; y < canvas.rows; ++y) {
        const auto* row = canvas.ptr<uint8_t>(y);
        for (int i = 0; i < canvas.cols * 3; ++i)
            out.rgb[static_cast<size_t>(y) * canvas.cols * 3 + i] = row[i] / 255.0f;
    }
    return out;
}

void write_comparison_sheet(const std::filesystem::path& path, const std::vector<SheetPanel>& panels,
                            io::WriteMode mode) {
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (extension != ".png" && extension != ".jpg" && extension != ".jpeg")
        throw InputError(path.string(), "a comparison sheet is written as .png, .jpg or .jpeg, not '" + extension + "'");
    const io::ImageRGB sheet = compose_comparison_sheet(panels);
    if (extension == ".png") {
        io::write_png_rgb(path, sheet.width, sheet.height, sheet.rgb.data(), 8, mode);
        return;
    }
    cv::Mat bgr(sheet.height, sheet.width, CV_8UC3);
    for (int y = 0; y < sheet.height; ++y) {
        auto* row = bgr.ptr<uint8_t>(y);
        const float* src = sheet.rgb.data() + static_cast<size_t>(y) * sheet.width * 3;
        for (int x = 0; x < sheet.width; ++x)
            for (int c = 0; c < 3; ++c) row[x * 3 + c] = to_byte(src[x * 3 + 2 - c]);
    }
    std::vector<uchar> bytes;
    if (!cv::imencode(".jpg", bgr, bytes, {cv::IMWRITE_JPEG_QUALITY, kJpegQuality}))
        throw InputError(path.string(), "JPEG encoding failed");
    io::write_file_atomically(path, mode, [&](std::ostream& out) {
        out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    });
}

int heat_bar_width(int h, float max_error) { return bar_layout(h, max_error).width; }

SheetPanel heat_map_panel(const float* a, const float* b, int w, int h, float max_error, std::string caption) {
    const std::vector<float> err = eval::error_map(a, b, w, h, 3);
    std::vector<uint8_t> heat;
    eval::colorize_heat(err, max_error, heat);

    const BarLayout bar = bar_layout(h, max_error);
    // The bar: a gradient from max_error (top) to 0 (bottom), coloured by the same ramp, with room
    // above and below for half a label.
    cv::Mat bar_image(h, bar.width, CV_8UC3, kWhite);
    int y_top = std::min(bar.text_height / 2 + 3, h / 4);
    int y_bottom = h - 1 - y_top;
    if (y_bottom < y_top) y_top = y_bottom = 0;
    std::vector<float> levels;
    for (int y = y_top; y <= y_bottom; ++y) {
        const float t = y_bottom == y_top ? 1.0f : static_cast<float>(y_bottom - y) / static_cast<float>(y_bottom - y_top);
        levels.push_back(t * max_error);
    }
    std::vector<uint8_t> ramp;
    eval::colorize_heat(levels, max_error, ramp);
    const int gx0 = bar.gradient_x, gx1 = bar.gradient_x + bar.gradient_width;  // [gx0, gx1)
    for (int y = y_top; y <= y_bottom; ++y) {
        auto* row = bar_image.ptr<uint8_t>(y);
        const uint8_t* c = ramp.data() + static_cast<size_t>(y - y_top) * 3;
        for (int x = gx0; x < gx1; ++x) std::copy(c, c + 3, row + x * 3);
    }
    cv::rectangle(bar_image, cv::Point(gx0 - 1, y_top - 1), cv::Point(gx1, y_bottom + 1), kOutline, 1);
    const int label_rows[3] = {y_bottom, (y_top + y_bottom) / 2, y_top};
    for (int i = 0; i < 3; ++i) {
        const int y = label_rows[i];
        cv::line(bar_image, cv::Point(gx1, y), cv::Point(gx1 + 4, y), kOutline, 1);
        cv::putText(bar_image, bar.labels[i], cv::Point(gx1 + 8, y + bar.text_height / 2), kFont, bar.scale, kText,
                    bar.thickness, cv::LINE_AA);
    }

    SheetPanel panel;
    panel.caption = std::move(caption);
    panel.width = w + bar.width;
    panel.height = h;
    panel.rgb.resize(static_cast<size_t>(panel.width) * h * 3);
    for (int y = 0; y < h; ++y) {
        float* dst = panel.rgb.data() + static_cast<size_t>(y) * panel.width * 3;
        const uint8_t* src = heat.data() + static_cast<size_t>(y) * w * 3;
        for (int i = 0; i < w * 3; ++i) dst[i] = src[i] / 255.0f;
        const auto* bar_row = bar_image.ptr<uint8_t>(y);
        for (int i = 0; i < bar.width * 3; ++i) dst[w * 3 + i] = bar_row[i] / 255.0f;
    }
    return panel;
}

}  // namespace vksplat::report
