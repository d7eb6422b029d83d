// report.html: structure, escaping, image references; and the sample report that
// report_screenshot_test.sh opens in a headless browser, with the check of its screenshot.
#include "vksplat/report/html_report.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "vksplat/error.hpp"
#include "vksplat/report/chart.hpp"
#include "vksplat/report/comparison_sheet.hpp"
#include "vksplat/io/image.hpp"
#include "support/text_files.hpp"

namespace vksplat::report {
namespace {

namespace fs = std::filesystem;

using test::count;
using test::read_text;

fs::path fresh_dir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("vksplat_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

TEST(HtmlReport, IsACompletePageWithoutScripts) {
    HtmlReport report("Pruning report");
    report.add_heading("Quality");
    report.add_paragraph("Lower is worse.");
    const std::string html = report.html();
    EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
    EXPECT_NE(html.find("<meta charset=\"utf-8\">"), std::string::npos);
    EXPECT_NE(html.find("<title>Pruning report</title>"), std::string::npos);
    EXPECT_NE(html.find("<h1>Pruning report</h1>"), std::string::npos);
    EXPECT_NE(html.find("<style>"), std::string::npos);
    EXPECT_EQ(html.find("<script"), std::string::npos);
    EXPECT_EQ(html.find("<link"), std::string::npos);  // no outside stylesheet
    EXPECT_EQ(html.find("http://"), std::string::npos);
    EXPECT_EQ(html.find("https://"), std::string::npos);
    // Blocks in the order added; every element opened is closed.
    EXPECT_LT(html.find("<h2>Quality</h2>"), html.find("<p>Lower is worse.</p>"));
    for (const char* tag : {"html", "head", "body", "main", "style", "h1", "h2", "p"})
        EXPECT_EQ(count(html, std::string("<") + tag + ">") + count(html, std::string("<") + tag + " "),
                  count(html, std::string("</") + tag + ">"))
            << tag;
}

TEST(HtmlReport, EscapesEveryText) {
    HtmlReport report("<b>bold</b> & co");
    report.add_heading("a < b");
    report.add_paragraph("x > y & \"z\"");
    report.add_table({"<th>"}, {{"<td>&"}});
    report.add_image("chart.svg", "caption \"quoted\" <img src=x onerror=alert(1)>");
    const std::string html = report.html();
    EXPECT_NE(html.find("<title>&lt;b&gt;bold&lt;/b&gt; &amp; co</title>"), std::string::npos);
    EXPECT_NE(html.find("<h2>a &lt; b</h2>"), std::string::npos);
    EXPECT_NE(html.find("<p>x &gt; y &amp; &quot;z&quot;</p>"), std::string::npos);
    EXPECT_NE(html.find("<th>&lt;th&gt;</th>"), std::string::npos);
    EXPECT_NE(html.find("<td>&lt;td&gt;&amp;</td>"), std::string::npos);
    EXPECT_NE(html.find("alt=\"caption &quot;quoted&quot; &lt;img src=x onerror=alert(1)&gt;\""), std::string::npos);
    EXPECT_EQ(html.find("<b>"), std::string::npos);
    EXPECT_EQ(count(html, "<img"), 1u);
}

TEST(HtmlReport, ReferencesImagesByRelativePath) {
    HtmlReport report("r");
    report.add_image("charts/psnr.svg", "PSNR against size");
    report.add_images_row({{"sheets/view 1.png", "view 1"}, {"sheets/\"odd\"&name#?.png", "odd"}});
    const std::string html = report.html();
    EXPECT_NE(html.find("<img src=\"charts/psnr.svg\" alt=\"PSNR against size\">"), std::string::npos);
    EXPECT_NE(html.find("<figcaption>PSNR against size</figcaption>"), std::string::npos);
    EXPECT_NE(html.find("src=\"sheets/view%201.png\""), std::string::npos);
    EXPECT_NE(html.find("src=\"sheets/%22odd%22%26name%23%3F.png\""), std::string::npos);
    EXPECT_EQ(count(html, "<figure>"), 3u);
    EXPECT_EQ(count(html, "<div class=\"row\">"), 1u);
    EXPECT_THROW(report.add_image("/abs/chart.svg", "x"), std::invalid_argument);
    EXPECT_THROW(report.add_image("", "x"), std::invalid_argument);
    EXPECT_THROW(report.add_images_row({{"ok.png", "a"}, {"/abs.png", "b"}}), std::invalid_argument);
}

TEST(HtmlReport, SetsSummariesAndWarningsApartFromParagraphs) {
    HtmlReport report("r");
    report.add_note("best trade: 80% fewer <Gaussians>", HtmlReport::Note::summary);
    report.add_note("timed on a CPU", HtmlReport::Note::warning);
    report.add_paragraph("plain");
    const std::string html = report.html();
    EXPECT_NE(html.find("<p class=\"note summary\">best trade: 80% fewer &lt;Gaussians&gt;</p>"), std::string::npos);
    EXPECT_NE(html.find("<p class=\"note warning\">timed on a CPU</p>"), std::string::npos);
    EXPECT_NE(html.find("p.warning {"), std::string::npos) << "styled";
    EXPECT_LT(html.find("note summary"), html.find("<p>plain</p>"));
}

TEST(HtmlReport, RightAlignsNumbersInTablesAndChecksRowWidths) {
    HtmlReport report("r");
    report.add_table({"method", "kept", "PSNR", "change"},
                     {{"opacity", "1.5e6", "31.42", "-3.5%"}, {"blend", "750000", "30.9", "+2%"}});
    const std::string html = report.html();
    EXPECT_NE(html.find("<td>opacity</td><td class=\"num\">1.5e6</td><td class=\"num\">31.42</td>"
                        "<td class=\"num\">-3.5%</td>"),
              std::string::npos);
    EXPECT_NE(html.find("<td class=\"num\">+2%</td>"), std::string::npos);
    EXPECT_EQ(count(html, "<tr>"), 3u);
    EXPECT_THROW(report.add_table({"a", "b"}, {{"1", "2"}, {"3"}}), std::invalid_argument);
    EXPECT_NO_THROW(report.add_table({}, {{"1"}, {"2", "3"}}));  // no header: any widths
    EXPECT_EQ(count(report.html(), "<thead>"), 1u);
}

TEST(HtmlReport, WritesAtomicallyAndRefusesToReplaceUnlessAsked) {
    const fs::path dir = fresh_dir("report_test");
    HtmlReport report("first");
    report.write(dir / "report.html", io::WriteMode::refuse_existing);
    EXPECT_EQ(read_text(dir / "report.html"), report.html());
    EXPECT_THROW(report.write(dir / "report.html", io::WriteMode::refuse_existing), InputError);
    HtmlReport second("second");
    second.write(dir / "report.html", io::WriteMode::overwrite);
    EXPECT_EQ(read_text(dir / "report.html"), second.html());
    fs::remove_all(dir);
}

// --- the sample report and its screenshot ------------------------------------------------------

// The first two series colours of every chart (Okabe-Ito blue and orange).
constexpr uint8_t kFirstColour[3] = {0x00, 0x72, 0xB2};
constexpr uint8_t kSecondColour[3] = {0xE6, 0x9F, 0x00};

// Writes report.html, two charts and a comparison sheet into `dir`, replacing earlier ones.
void write_sample_report(const fs::path& dir) {
    fs::create_directories(dir / "charts");
    const auto mode = io::WriteMode::overwrite;
    const double nan = std::numeric_limits<double>::quiet_NaN();

    ChartSpec size;
    size.title = "PSNR against size";
    size.x_label = "Gaussians kept";
    size.y_label = "PSNR (dB)";
    size.log_x = true;
    size.series.push_back({"opacity", {2e5, 4e5, 8e5, 1.6e6, 3.2e6}, {24.1, 26.8, 28.9, 30.2, 30.8}});
    size.series.push_back({"blend weight", {2e5, 4e5, 8e5, 1.6e6, 3.2e6}, {26.0, 28.4, nan, 30.7, 30.9}});
    size.series.push_back({"footprint", {2e5, 4e5, 8e5, 1.6e6, 3.2e6}, {25.0, 27.2, 29.4, 30.3, 30.8}});
    size.reference_lines.push_back({31.0, "unpruned"});
    write_svg_chart(dir / "charts" / "psnr_vs_size.svg", size, mode, 540, 380);

    const ChartSpec sh = paired_chart("PSNR per test view by SH degree", "PSNR (dB)", {"SH 0", "SH 1", "SH 2", "SH 3"},
                                      {{27.1, 28.3, 28.9, 29.2},
                                       {29.5, 30.4, 30.9, 31.0},
                                       {25.2, 26.0, 26.7, 26.9},
                                       {28.0, 28.2, 28.8, 29.6},
                                       {30.1, 31.5, 31.9, 32.0}});
    write_svg_chart(dir / "charts" / "psnr_by_sh.svg", sh, mode, 540, 380);

    // A comparison sheet of a grey test picture: photo | render | heat map.
    const int w = 160, h = 120;
    std::vector<float> photo(static_cast<size_t>(w) * h * 3), render(photo.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float v = ((x / 20 + y / 20) % 2 == 0) ? 0.8f : 0.3f;
            // A blurry patch, as pruning leaves where small Gaussians went.
            const float dx = static_cast<float>(x - 110), dy = static_cast<float>(y - 55);
            const float noise = 0.09f * std::exp(-(dx * dx + dy * dy) / 500.0f) + 0.01f * std::sin(0.7f * x);
            for (int c = 0; c < 3; ++c) {
                const size_t i = (static_cast<size_t>(y) * w + x) * 3 + c;
                photo[i] = v;
                render[i] = v + noise;
            }
        }
    write_comparison_sheet(dir / "sheet.png",
                           {{"photo", w, h, photo}, {"render", w, h, render},
                            heat_map_panel(photo.data(), render.data(), w, h, 0.1f, "error")},
                           mode);

    HtmlReport report("vksplat sample report");
    report.add_paragraph("Written by tests/report/report_test.cpp for report_screenshot_test.sh: two charts and a "
                         "comparison sheet, with made-up numbers.");
    report.add_heading("Size and quality");
    report.add_table({"method", "Gaussians kept", "PSNR", "SSIM"},
                     {{"unpruned", "3.2M", "31.00", "0.921"},
                      {"opacity", "800k", "28.90", "0.894"},
                      {"blend weight", "800k", "29.60", "0.903"}});
    report.add_images_row({{"charts/psnr_vs_size.svg", "PSNR against the number of Gaussians kept"},
                           {"charts/psnr_by_sh.svg", "PSNR of each test view at SH degrees 0 to 3"}});
    report.add_heading("View 1");
    report.add_image("sheet.png", "photo | render | error (mean absolute, 0 to 0.1)");
    report.write(dir / "report.html", mode);
}

struct ScreenshotStats {
    size_t pixels = 0;
    size_t first_colour = 0, second_colour = 0;  // pixels within a small distance of each
    double off_background = 0;                   // fraction unlike the most common colour
};

ScreenshotStats screenshot_stats(const io::ImageRGB& image) {
    ScreenshotStats s;
    s.pixels = static_cast<size_t>(image.width) * image.height;
    std::map<uint32_t, size_t> histogram;
    auto near = [](const uint8_t* p, const uint8_t* c) {
        return std::abs(p[0] - c[0]) + std::abs(p[1] - c[1]) + std::abs(p[2] - c[2]) <= 30;
    };
    for (size_t i = 0; i < s.pixels; ++i) {
        uint8_t p[3];
        for (int c = 0; c < 3; ++c) p[c] = static_cast<uint8_t>(std::lround(image.rgb[i * 3 + c] * 255.0f));
        ++histogram[(uint32_t(p[0]) << 16) | (uint32_t(p[1]) << 8) | p[2]];
        if (near(p, kFirstColour)) ++s.first_colour;
        if (near(p, kSecondColour)) ++s.second_colour;
    }
    size_t most = 0;
    for (const auto& [colour, n] : histogram) most = std::max(most, n);
    s.off_background = s.pixels == 0 ? 0.0 : 1.0 - static_cast<double>(most) / s.pixels;
    return s;
}

// What a screenshot of the sample report must show: a page that is not blank, and both charts'
// lines and markers in their colours.
::testing::AssertionResult looks_like_the_sample_report(const io::ImageRGB& image) {
    const ScreenshotStats s = screenshot_stats(image);
    std::ostringstream why;
    why << image.width << " x " << image.height << ": " << s.off_background * 100
        << "% off the background colour, " << s.first_colour << " pixels of the first series colour, "
        << s.second_colour << " of the second";
    if (s.off_background < 0.03 || s.first_colour < 300 || s.second_colour < 300)
        return ::testing::AssertionFailure() << why.str();
    return ::testing::AssertionSuccess() << why.str();
}

TEST(SampleReport, WritesAReportWithTwoChartsAndASheet) {
    // report_screenshot_test.sh names the folder; otherwise this is a test of its own.
    const char* named = std::getenv("VKSPLAT_SAMPLE_REPORT_DIR");
    const fs::path dir = named != nullptr && *named != '\0' ? fs::path(named) : fresh_dir("sample_report");
    write_sample_report(dir);
    const std::string html = read_text(dir / "report.html");
    for (const char* file : {"charts/psnr_vs_size.svg", "charts/psnr_by_sh.svg", "sheet.png"}) {
        EXPECT_TRUE(fs::is_regular_file(dir / file)) << file;
        EXPECT_NE(html.find(std::string("src=\"") + file + "\""), std::string::npos) << file;
    }
    const io::ImageRGB sheet = io::read_image_rgb(dir / "sheet.png", {1, 1, 1});
    EXPECT_EQ(sheet.width, 160 + 160 + 160 + heat_bar_width(120, 0.1f));
    if (named == nullptr || *named == '\0') fs::remove_all(dir);
}

TEST(ReportScreenshot, FindsBothChartColoursOnlyWhenTheyAreThere) {
    // report_screenshot_test.sh passes a browser's screenshot of the sample report.
    const char* shot = std::getenv("VKSPLAT_REPORT_SCREENSHOT");
    if (shot != nullptr && *shot != '\0') {
        const io::ImageRGB image = io::read_image_rgb(shot, {1, 1, 1});
        EXPECT_TRUE(looks_like_the_sample_report(image));
        std::cout << "screenshot " << shot << ": " << looks_like_the_sample_report(image).message() << "\n";
        return;
    }
    // Otherwise, check the check: a blank page fails; lines of both colours pass; one is not enough.
    io::ImageRGB page{400, 300, std::vector<float>(400 * 300 * 3, 0.96f)};
    EXPECT_FALSE(looks_like_the_sample_report(page));
    auto paint = [&](int y0, const uint8_t* colour) {
        for (int y = y0; y < y0 + 8; ++y)
            for (int x = 20; x < 380; ++x)
                for (int c = 0; c < 3; ++c) page.rgb[(static_cast<size_t>(y) * 400 + x) * 3 + c] = colour[c] / 255.0f;
    };
    paint(100, kFirstColour);
    EXPECT_FALSE(looks_like_the_sample_report(page));
    paint(200, kSecondColour);
    EXPECT_TRUE(looks_like_the_sample_report(page));
}

}  // namespace
}  // namespace vksplat::report
