// SVG line charts: tick values, structure of the document, gaps, escaping, legends.
#include "vksplat/report/chart.hpp"

#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include "vksplat/error.hpp"
#include "support/text_files.hpp"

namespace vksplat::report {
namespace {

using test::count;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// A small, strict XML checker: balanced and properly nested tags, one root element, quoted and
// unique attributes, no stray '<', and only defined entities. Counts elements by name.
struct XmlCheck {
    bool ok = true;
    std::string error;
    std::map<std::string, int> elements;
};

bool valid_entity(const std::string& s, size_t amp, size_t* end) {
    const size_t semi = s.find(';', amp);
    if (semi == std::string::npos || semi - amp > 10) return false;
    const std::string name = s.substr(amp + 1, semi - amp - 1);
    *end = semi + 1;
    if (name == "amp" || name == "lt" || name == "gt" || name == "quot" || name == "apos") return true;
    if (name.size() >= 2 && name[0] == '#') {
        const bool hex = name[1] == 'x';
        for (size_t i = hex ? 2 : 1; i < name.size(); ++i)
            if (!(hex ? std::isxdigit(static_cast<unsigned char>(name[i])) : std::isdigit(static_cast<unsigned char>(name[i]))))
                return false;
        return name.size() > (hex ? 2u : 1u);
    }
    return false;
}

XmlCheck check_xml(const std::string& s) {
    XmlCheck r;
    auto fail = [&](const std::string& why, size_t at) {
        r.ok = false;
        r.error = why + " at byte " + std::to_string(at) + ": '" + s.substr(at, 40) + "'";
        return r;
    };
    auto is_name_char = [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == ':' || c == '-' || c == '.';
    };
    std::vector<std::string> stack;
    int roots = 0;
    size_t i = 0;
    while (i < s.size()) {
        if (s[i] == '<') {
            if (s.compare(i, 2, "<?") == 0) {
                const size_t e = s.find("?>", i);
                if (e == std::string::npos) return fail("unterminated declaration", i);
                i = e + 2;
            } else if (s.compare(i, 4, "<!--") == 0) {
                const size_t e = s.find("-->", i);
                if (e == std::string::npos) return fail("unterminated comment", i);
                i = e + 3;
            } else if (s.compare(i, 2, "</") == 0) {
                size_t j = i + 2;
                while (j < s.size() && is_name_char(s[j])) ++j;
                const std::string name = s.substr(i + 2, j - i - 2);
                while (j < s.size() && std::isspace(static_cast<unsigned char>(s[j]))) ++j;
                if (j >= s.size() || s[j] != '>') return fail("bad end tag", i);
                if (stack.empty() || stack.back() != name) return fail("mismatched end tag", i);
                stack.pop_back();
                i = j + 1;
            } else {
                size_t j = i + 1;
                while (j < s.size() && is_name_char(s[j])) ++j;
                const std::string name = s.substr(i + 1, j - i - 1);
                if (name.empty() || std::isdigit(static_cast<unsigned char>(name[0]))) return fail("bad tag name", i);
                if (stack.empty() && ++roots > 1) return fail("second root element", i);
                ++r.elements[name];
                std::map<std::string, int> attributes;
                bool closed = false;
                while (true) {
                    const size_t before = j;
                    while (j < s.size() && std::isspace(static_cast<unsigned char>(s[j]))) ++j;
                    if (j >= s.size()) return fail("unterminated tag", i);
                    if (s.compare(j, 2, "/>") == 0) {
                        j += 2;
                        closed = true;
                        break;
                    }
                    if (s[j] == '>') {
                        ++j;
                        break;
                    }
                    if (j == before) return fail("no space before attribute", j);
                    const size_t a = j;
                    while (j < s.size() && is_name_char(s[j])) ++j;
                    const std::string attribute = s.substr(a, j - a);
                    if (attribute.empty()) return fail("bad attribute", a);
                    if (++attributes[attribute] > 1) return fail("duplicate attribute " + attribute, a);
                    if (j >= s.size() || s[j] != '=') return fail("attribute without '='", j);
                    ++j;
                    if (j >= s.size() || (s[j] != '"' && s[j] != '\'')) return fail("unquoted attribute", j);
                    const char quote = s[j];
                    const size_t v = ++j;
                    const size_t e = s.find(quote, v);
                    if (e == std::string::npos) return fail("unterminated attribute", v);
                    for (size_t k = v; k < e; ++k) {
                        if (s[k] == '<') return fail("'<' in attribute", k);
                        size_t end = 0;
                        if (s[k] == '&' && !valid_entity(s, k, &end)) return fail("bad entity", k);
                    }
                    j = e + 1;
                }
                if (!closed) stack.push_back(name);
                i = j;
            }
        } else {
            if (s[i] == '&') {
                size_t end = 0;
                if (!valid_entity(s, i, &end)) return fail("bad entity", i);
                i = end;
                continue;
            }
            if (s[i] == '>') return fail("stray '>'", i);
            if (stack.empty() && !std::isspace(static_cast<unsigned char>(s[i]))) return fail("text outside root", i);
            ++i;
        }
    }
    if (!stack.empty()) return fail("unclosed <" + stack.back() + ">", s.size());
    if (roots != 1) return fail("no root element", 0);
    return r;
}

// The (cx, cy) of every circle marker, in document order.
std::vector<std::pair<double, double>> circle_markers(const std::string& svg) {
    std::vector<std::pair<double, double>> out;
    const std::regex re(R"re(<circle class="marker"[^>]*cx="([-0-9.]+)" cy="([-0-9.]+)")re");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), re); it != std::sregex_iterator(); ++it)
        out.emplace_back(std::stod((*it)[1]), std::stod((*it)[2]));
    return out;
}

// The text of every <text> element, unescaped only as far as the tests need.
std::vector<std::string> texts(const std::string& svg) {
    std::vector<std::string> out;
    const std::regex re(R"re(<text[^>]*>([^<]*)</text>)re");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), re); it != std::sregex_iterator(); ++it)
        out.push_back((*it)[1]);
    return out;
}

bool has_text(const std::string& svg, const std::string& t) {
    for (const std::string& s : texts(svg))
        if (s == t) return true;
    return false;
}

// --- ticks -------------------------------------------------------------------------------------

TEST(NiceTicks, GivesRoundStepsCoveringTheRange) {
    EXPECT_EQ(nice_ticks(0.0, 1.0), (std::vector<double>{0.0, 0.2, 0.4, 0.6, 0.8, 1.0}));
    EXPECT_EQ(nice_ticks(27.3, 31.9), (std::vector<double>{27, 28, 29, 30, 31, 32}));
    EXPECT_EQ(nice_ticks(-3.0, 7.0), (std::vector<double>{-4, -2, 0, 2, 4, 6, 8}));
    EXPECT_EQ(nice_ticks(0.0, 2.5e6), (std::vector<double>{0, 5e5, 1e6, 1.5e6, 2e6, 2.5e6}));
    EXPECT_EQ(nice_ticks(0.013, 0.087),
              (std::vector<double>{0.01, 0.02, 0.03, 0.04, 0.05, 0.06, 0.07, 0.08, 0.09}));
    EXPECT_EQ(nice_ticks(0.91, 0.97), (std::vector<double>{0.91, 0.92, 0.93, 0.94, 0.95, 0.96, 0.97}));
    // Exact decimal multiples do not grow an extra tick through rounding (0.3 / 0.1 < 3 in doubles).
    EXPECT_EQ(nice_ticks(0.3, 0.7, 4), (std::vector<double>{0.3, 0.4, 0.5, 0.6, 0.7}));
}

TEST(NiceTicks, WidensAnEmptyRangeAroundTheValue) {
    for (double v : {0.0, 5.0, -120.0, 3e-5}) {
        const std::vector<double> t = nice_ticks(v, v);
        ASSERT_GE(t.size(), 3u) << v;
        EXPECT_LT(t.front(), v);
        EXPECT_GT(t.back(), v);
    }
}

TEST(NiceTicks, HoldsItsPromisesOnRandomRanges) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> exponent(-6.0, 9.0), unit(-1.0, 1.0);
    for (int trial = 0; trial < 2000; ++trial) {
        const double scale = std::pow(10.0, exponent(rng));
        double lo = unit(rng) * scale, hi = unit(rng) * scale;
        if (lo > hi) std::swap(lo, hi);
        const std::vector<double> t = nice_ticks(lo, hi);
        ASSERT_GE(t.size(), 2u);
        EXPECT_LE(t.size(), 12u) << lo << " " << hi;
        EXPECT_LE(t.front(), lo + std::abs(lo) * 1e-12);
        EXPECT_GE(t.back(), hi - std::abs(hi) * 1e-12);
        const double step = t[1] - t[0];
        const double mantissa = step / std::pow(10.0, std::floor(std::log10(step) + 1e-9));
        EXPECT_TRUE(std::abs(mantissa - 1) < 1e-6 || std::abs(mantissa - 2) < 1e-6 || std::abs(mantissa - 5) < 1e-6)
            << "step " << step;
        for (size_t i = 1; i < t.size(); ++i) EXPECT_NEAR(t[i] - t[i - 1], step, step * 1e-6);
    }
}

TEST(NiceTicks, RejectsBadRanges) {
    EXPECT_THROW(nice_ticks(1.0, 0.0), std::invalid_argument);
    EXPECT_THROW(nice_ticks(kNaN, 1.0), std::invalid_argument);
    EXPECT_THROW(nice_ticks(0.0, kInf), std::invalid_argument);
    EXPECT_THROW(nice_ticks(-1e308, 1e308), std::invalid_argument);
}

TEST(LogTicks, GivesDecadesAndOneTwoFiveWithinShortRanges) {
    EXPECT_EQ(log_ticks(1.0, 1000.0), (std::vector<double>{1, 10, 100, 1000}));
    EXPECT_EQ(log_ticks(0.003, 40.0), (std::vector<double>{0.001, 0.01, 0.1, 1, 10, 100}));
    EXPECT_EQ(log_ticks(2e5, 9e5), (std::vector<double>{2e5, 5e5, 1e6}));
    EXPECT_EQ(log_ticks(3e4, 8e5), (std::vector<double>{2e4, 5e4, 1e5, 2e5, 5e5, 1e6}));
    EXPECT_EQ(log_ticks(2e5, 3.2e6), (std::vector<double>{2e5, 5e5, 1e6, 2e6, 5e6}));
    EXPECT_EQ(log_ticks(0.5, 0.5), (std::vector<double>{0.5, 1}));
    EXPECT_EQ(log_ticks(3e4, 2e6), (std::vector<double>{1e4, 1e5, 1e6, 1e7}));  // three decades: powers only
    EXPECT_EQ(log_ticks(1000.0, 1000.0), (std::vector<double>{1000, 2000}));
    EXPECT_THROW(log_ticks(0.0, 10.0), std::invalid_argument);
    EXPECT_THROW(log_ticks(-1.0, 10.0), std::invalid_argument);
    EXPECT_THROW(log_ticks(10.0, 1.0), std::invalid_argument);
}

TEST(TickLabels, AreShortAndDistinct) {
    using V = std::vector<std::string>;
    EXPECT_EQ(tick_labels({0, 0.2, 0.4, 0.6}), (V{"0", "0.2", "0.4", "0.6"}));
    EXPECT_EQ(tick_labels({0.91, 0.92, 0.93}), (V{"0.91", "0.92", "0.93"}));
    EXPECT_EQ(tick_labels({27, 28, 29}), (V{"27", "28", "29"}));
    EXPECT_EQ(tick_labels({-0.1, 0, 0.1}), (V{"-0.1", "0", "0.1"}));
    EXPECT_EQ(tick_labels({0, 2000, 4000, 6000}), (V{"0", "2000", "4000", "6000"}));
    EXPECT_EQ(tick_labels({0, 5000, 10000, 15000}), (V{"0", "5k", "10k", "15k"}));
    EXPECT_EQ(tick_labels({0, 5e5, 1e6, 1.5e6}), (V{"0", "0.5M", "1M", "1.5M"}));
    EXPECT_EQ(tick_labels({2e9, 4e9}), (V{"2G", "4G"}));
    EXPECT_EQ(tick_labels(nice_ticks(0.0, 2.5e6)), (V{"0", "0.5M", "1M", "1.5M", "2M", "2.5M"}));
    EXPECT_EQ(tick_labels({0.001, 0.01, 0.1, 1, 10, 100, 1000, 1e4, 2e5, 1e6}, true),
              (V{"0.001", "0.01", "0.1", "1", "10", "100", "1k", "10k", "200k", "1M"}));
}

// --- the SVG document --------------------------------------------------------------------------

ChartSpec three_series() {
    ChartSpec spec;
    spec.title = "PSNR against size";
    spec.x_label = "Gaussians kept";
    spec.y_label = "PSNR (dB)";
    spec.series.push_back({"opacity", {1e5, 2e5, 3e5, 4e5, 5e5}, {25.0, 27.5, 29.0, 30.0, 30.5}});
    spec.series.push_back({"blend weight", {1e5, 2e5, 3e5, 4e5, 5e5}, {26.0, 28.0, kNaN, 30.2, 30.6}});
    spec.series.push_back({"single", {3e5}, {28.0}});
    return spec;
}

TEST(SvgChart, IsWellFormedXmlWithTheSeriesLinesAndMarkers) {
    const std::string svg = render_svg_chart(three_series());
    const XmlCheck xml = check_xml(svg);
    ASSERT_TRUE(xml.ok) << xml.error;
    EXPECT_EQ(xml.elements.at("svg"), 1);
    EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
    EXPECT_NE(svg.find("xmlns=\"http://www.w3.org/2000/svg\""), std::string::npos);
    EXPECT_NE(svg.find("width=\"720\" height=\"440\""), std::string::npos);
    // Series 1: one line; series 2: broken by the NaN into two; series 3: a lone point, no line.
    EXPECT_EQ(xml.elements.at("polyline"), 3);
    EXPECT_EQ(count(svg, "class=\"series\""), 3u);
    EXPECT_EQ(count(svg, "class=\"marker\""), 5u + 4u + 1u);
    EXPECT_EQ(count(svg, "class=\"legend-marker\""), 3u);
    for (const char* name : {"opacity", "blend weight", "single"}) EXPECT_TRUE(has_text(svg, name)) << name;
    for (const char* label : {"PSNR against size", "Gaussians kept", "PSNR (dB)"}) EXPECT_TRUE(has_text(svg, label));
    // Okabe-Ito colours, one per series.
    EXPECT_NE(svg.find("stroke=\"#0072B2\""), std::string::npos);
    EXPECT_NE(svg.find("stroke=\"#E69F00\""), std::string::npos);
    // Nice ticks on both axes, formatted with suffixes.
    for (const char* tick : {"100k", "200k", "500k", "25", "26", "31"}) EXPECT_TRUE(has_text(svg, tick)) << tick;
}

TEST(SvgChart, PlacesPointsInsideThePlotInOrder) {
    ChartSpec spec;
    spec.series.push_back({"rising", {0, 1, 2, 3}, {0, 1, 2, 3}});
    const std::string svg = render_svg_chart(spec, 600, 400);
    const auto points = circle_markers(svg);
    ASSERT_EQ(points.size(), 4u);
    for (size_t i = 1; i < points.size(); ++i) {
        EXPECT_GT(points[i].first, points[i - 1].first);
        EXPECT_LT(points[i].second, points[i - 1].second);  // SVG y grows downwards
    }
    for (const auto& [x, y] : points) {
        EXPECT_GT(x, 0);
        EXPECT_LT(x, 600);
        EXPECT_GT(y, 0);
        EXPECT_LT(y, 400);
    }
}

TEST(SvgChart, LeavesGapsAtNonFinitePoints) {
    ChartSpec spec;
    spec.series.push_back({"gappy", {0, 1, 2, 3, 4, 5, 6, 7}, {1, kNaN, 2, kInf, 3, 4, 5, -kInf}});
    spec.series.push_back({"bad x", {kNaN, 1, 2}, {1, 2, 3}});
    const std::string svg = render_svg_chart(spec);
    const XmlCheck xml = check_xml(svg);
    ASSERT_TRUE(xml.ok) << xml.error;
    // Runs: {0}, {2}, {4, 5, 6} for the first; {1, 2} for the second.
    EXPECT_EQ(xml.elements.at("polyline"), 2);
    EXPECT_EQ(count(svg, "class=\"marker\""), 5u + 2u);
    EXPECT_EQ(svg.find("nan"), std::string::npos);
    EXPECT_EQ(svg.find("inf"), std::string::npos);
}

TEST(SvgChart, LogAxisSkipsPointsThatAreNotPositive) {
    ChartSpec spec;
    spec.log_x = true;
    spec.series.push_back({"size", {0, 1e3, 1e4, -5, 1e5, 1e6}, {1, 2, 3, 4, 5, 6}});
    const std::string svg = render_svg_chart(spec);
    ASSERT_TRUE(check_xml(svg).ok);
    EXPECT_EQ(count(svg, "<polyline"), 2u);  // {1e3, 1e4}, {1e5, 1e6}
    EXPECT_EQ(count(svg, "class=\"marker\""), 4u);
    for (const char* tick : {"1k", "10k", "100k", "1M"}) EXPECT_TRUE(has_text(svg, tick)) << tick;
    // Decades are evenly spaced.
    const auto p = circle_markers(svg);
    ASSERT_EQ(p.size(), 4u);
    EXPECT_NEAR(p[1].first - p[0].first, p[2].first - p[1].first, 0.02);
    EXPECT_NEAR(p[2].first - p[1].first, p[3].first - p[2].first, 0.02);
}

TEST(SvgChart, EscapesTextForXml) {
    ChartSpec spec;
    spec.title = "a < b & c > d";
    spec.x_label = "\"quoted\" & 'single'";
    spec.y_label = "<script>alert(1)</script>";
    spec.series.push_back({"name <with> & \"quotes\"", {1, 2}, {1, 2}});
    spec.reference_lines.push_back({1.5, "R&D <ref>"});
    const std::string svg = render_svg_chart(spec);
    const XmlCheck xml = check_xml(svg);
    ASSERT_TRUE(xml.ok) << xml.error;
    EXPECT_NE(svg.find("a &lt; b &amp; c &gt; d"), std::string::npos);
    EXPECT_NE(svg.find("&quot;quoted&quot; &amp; &#39;single&#39;"), std::string::npos);
    EXPECT_NE(svg.find("data-name=\"name &lt;with&gt; &amp; &quot;quotes&quot;\""), std::string::npos);
    EXPECT_NE(svg.find("R&amp;D &lt;ref&gt;"), std::string::npos);
    EXPECT_EQ(svg.find("<script"), std::string::npos);
    EXPECT_EQ(xml.elements.count("script"), 0u);
}

TEST(XmlEscape, DropsControlCharactersAndKeepsUtf8) {
    EXPECT_EQ(xml_escape("a\x01" "b\tc\nd"), "ab\tc\nd");
    EXPECT_EQ(xml_escape("\xCE\x94 PSNR \xE2\x89\xA5 30"), "\xCE\x94 PSNR \xE2\x89\xA5 30");
    EXPECT_EQ(xml_escape("<&>\"'"), "&lt;&amp;&gt;&quot;&#39;");
}

TEST(SvgChart, DrawsAxesAndSaysSoWhenThereIsNoData) {
    ChartSpec empty_series, all_nan;
    empty_series.series.push_back({"nothing", {}, {}});
    all_nan.series.push_back({"nan", {1, 2}, {kNaN, kNaN}});
    all_nan.log_x = true;
    for (const ChartSpec& spec : {ChartSpec{}, empty_series, all_nan}) {
        const std::string svg = render_svg_chart(spec);
        const XmlCheck xml = check_xml(svg);
        ASSERT_TRUE(xml.ok) << xml.error;
        EXPECT_TRUE(has_text(svg, "no data"));
        EXPECT_EQ(count(svg, "<polyline"), 0u);
        EXPECT_EQ(count(svg, "class=\"marker\""), 0u);
    }
}

TEST(SvgChart, DrawsASinglePointOnANonEmptyAxis) {
    ChartSpec spec;
    spec.series.push_back({"one", {5}, {30}});
    const std::string svg = render_svg_chart(spec);
    ASSERT_TRUE(check_xml(svg).ok);
    EXPECT_EQ(count(svg, "<polyline"), 0u);
    const auto p = circle_markers(svg);
    ASSERT_EQ(p.size(), 1u);
    EXPECT_FALSE(has_text(svg, "no data"));
    EXPECT_TRUE(has_text(svg, "30"));
    EXPECT_TRUE(has_text(svg, "5"));
}

TEST(SvgChart, DrawsReferenceLinesAndWidensTheAxisToShowThem) {
    ChartSpec spec;
    spec.series.push_back({"pruned", {1, 2, 3}, {27, 28, 29}});
    spec.reference_lines.push_back({32.4, "unpruned"});
    const std::string svg = render_svg_chart(spec);
    ASSERT_TRUE(check_xml(svg).ok);
    EXPECT_EQ(count(svg, "stroke-dasharray"), 1u);
    EXPECT_TRUE(has_text(svg, "unpruned"));
    EXPECT_TRUE(has_text(svg, "33"));  // the axis reaches past 32.4
}

TEST(SvgChart, HonoursAFixedYRange) {
    ChartSpec spec;
    spec.series.push_back({"ssim", {1, 2, 3}, {0.91, 0.95, 1.2}});
    spec.y_min = 0.9;
    spec.y_max = 1.0;
    spec.reference_lines.push_back({0.5, "below the range"});
    const std::string svg = render_svg_chart(spec);
    ASSERT_TRUE(check_xml(svg).ok);
    EXPECT_TRUE(has_text(svg, "0.9"));
    EXPECT_TRUE(has_text(svg, "1"));
    EXPECT_EQ(count(svg, "class=\"marker\""), 2u) << "1.2 lies above the range: an off-scale marker";
    EXPECT_FALSE(has_text(svg, "below the range"));  // outside the fixed range: not drawn
    EXPECT_EQ(count(svg, "clip-path=\"url(#plot-area)\""), 1u);
    spec.y_max = 0.9;
    EXPECT_THROW(render_svg_chart(spec), std::invalid_argument);
}

// The triangles' tips ("M... L... L x tip Z"): the y of each off-scale marker's tip, in order.
std::vector<std::pair<double, double>> off_scale_tips(const std::string& svg) {
    std::vector<std::pair<double, double>> out;
    const std::regex re(R"re(<path class="off-scale"[^>]*d="M[-0-9.]+ ([-0-9.]+)L[-0-9.]+ [-0-9.]+L([-0-9.]+) ([-0-9.]+)Z")re");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), re); it != std::sregex_iterator(); ++it)
        out.emplace_back(std::stod((*it)[2]), std::stod((*it)[3]) - std::stod((*it)[1]));  // x, tip - base
    return out;
}

// The zoomed PSNR-change chart of a sweep where every method loses more than its range shows: each
// point is a triangle at the edge with its value, not an empty plot.
TEST(SvgChart, MarksPointsBeyondAFixedRangeAtTheEdgeWithTheirValues) {
    ChartSpec spec;
    spec.series.push_back({"blend", {0.5, 0.8, 0.9}, {-2.5, -3.14, -4}});
    spec.series.push_back({"random", {0.5, 0.8, 0.9}, {-2.25, -5.5, 0.75}});
    spec.y_min = -2.0;
    spec.y_max = 0.5;
    const std::string svg = render_svg_chart(spec, 620, 400);
    const XmlCheck xml = check_xml(svg);
    ASSERT_TRUE(xml.ok) << xml.error;
    EXPECT_EQ(count(svg, "class=\"marker\""), 0u);
    EXPECT_EQ(count(svg, "class=\"off-scale\""), 6u);
    for (const char* value : {"-2.5", "-3.14", "-4", "-2.25", "-5.5", "0.75"}) EXPECT_TRUE(has_text(svg, value)) << value;
    EXPECT_TRUE(has_text(svg, "off scale (value shown)"));
    EXPECT_EQ(count(svg, "class=\"legend-off-scale\""), 1u);
    EXPECT_FALSE(has_text(svg, "no data"));

    const auto tips = off_scale_tips(svg);
    ASSERT_EQ(tips.size(), 6u);
    // Below the range they point down, above it up; all sit inside the picture.
    for (size_t i : {0, 1, 2, 3, 4}) EXPECT_GT(tips[i].second, 0) << i;
    EXPECT_LT(tips[5].second, 0);
    const std::regex tip_y(R"re(<path class="off-scale"[^>]*L[-0-9.]+ ([-0-9.]+)Z")re");
    std::vector<double> ys;
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), tip_y); it != std::sregex_iterator(); ++it)
        ys.push_back(std::stod((*it)[1]));
    ASSERT_EQ(ys.size(), 6u);
    for (double y : ys) {
        EXPECT_GT(y, 0);
        EXPECT_LT(y, 400);
    }
    EXPECT_LT(ys[5], ys[0]) << "above the range: at the top edge";
    // Two points below at one x are stacked, not drawn over each other.
    EXPECT_EQ(tips[0].first, tips[3].first);
    EXPECT_NE(ys[0], ys[3]);

    // Without a fixed range nothing is off scale and the legend says nothing of it.
    spec.y_min.reset();
    spec.y_max.reset();
    const std::string free = render_svg_chart(spec, 620, 400);
    EXPECT_EQ(count(free, "class=\"off-scale\""), 0u);
    EXPECT_FALSE(has_text(free, "off scale (value shown)"));
}

TEST(SvgChart, DrawsTheSpreadOfEachXAsABar) {
    ChartSpec spec;
    Series timed{"blend", {2, 4, 8}, {30, 29, 27}};
    timed.x_low = {1.5, 3.9, kNaN};
    timed.x_high = {2.5, 60, 9};
    spec.series.push_back(timed);
    spec.log_x = true;
    const std::string svg = render_svg_chart(spec);
    ASSERT_TRUE(check_xml(svg).ok);
    EXPECT_EQ(count(svg, "class=\"spread\""), 2u) << "the NaN low end draws no bar";
    EXPECT_TRUE(has_text(svg, "100")) << "the axis widens to the bar's high end, 60";
    spec.series[0].x_high.pop_back();
    EXPECT_THROW(render_svg_chart(spec), std::invalid_argument);
}

TEST(SvgChart, ListsManySeriesInTheLegendWithDistinctStyles) {
    ChartSpec spec;
    for (int i = 0; i < 20; ++i)
        spec.series.push_back({"view " + std::to_string(i + 1), {0, 1}, {20.0 + i, 21.0 + i}});
    const std::string svg = render_svg_chart(spec);
    const XmlCheck xml = check_xml(svg);
    ASSERT_TRUE(xml.ok) << xml.error;
    for (int i = 0; i < 20; ++i) EXPECT_TRUE(has_text(svg, "view " + std::to_string(i + 1))) << i;
    EXPECT_EQ(count(svg, "class=\"legend-marker\""), 20u);
    // Past the 8 palette colours, the marker shape changes.
    EXPECT_EQ(count(svg, "<circle class=\"legend-marker\""), 8u);
    EXPECT_EQ(count(svg, "<rect class=\"legend-marker\""), 8u);
    EXPECT_EQ(count(svg, "<path class=\"legend-marker\""), 4u);
}

TEST(SvgChart, ShortensLongLegendNames) {
    ChartSpec spec;
    const std::string long_name(300, 'x');
    spec.series.push_back({long_name, {0, 1}, {0, 1}});
    spec.series.push_back({"", {0, 1}, {1, 0}});  // unnamed: no legend entry
    const std::string svg = render_svg_chart(spec);
    ASSERT_TRUE(check_xml(svg).ok);
    EXPECT_FALSE(has_text(svg, long_name));
    EXPECT_NE(svg.find("xxx\xE2\x80\xA6</text>"), std::string::npos);
    EXPECT_EQ(count(svg, "class=\"legend-marker\""), 1u);
}

TEST(SvgChart, RejectsMismatchedSeriesAndTinySizes) {
    ChartSpec spec;
    spec.series.push_back({"bad", {1, 2, 3}, {1, 2}});
    EXPECT_THROW(render_svg_chart(spec), std::invalid_argument);
    EXPECT_THROW(render_svg_chart(ChartSpec{}, 100, 100), std::invalid_argument);
}

TEST(PairedChart, PutsCategoriesOnTheXAxisAndOneLinePerItem) {
    const ChartSpec spec = paired_chart("PSNR per view by SH degree", "PSNR (dB)", {"SH 0", "SH 1", "SH 2", "SH 3"},
                                        {{28, 29, 29.5, 29.7}, {30, 30.5, 31, 31.2}, {25, kNaN, 26, 26.1}});
    ASSERT_EQ(spec.series.size(), 3u);
    EXPECT_EQ(spec.series[0].name, "view 1");
    EXPECT_EQ(spec.series[2].name, "view 3");
    EXPECT_EQ(spec.series[1].x, (std::vector<double>{0, 1, 2, 3}));
    EXPECT_EQ(spec.x_tick_labels, (std::vector<std::string>{"SH 0", "SH 1", "SH 2", "SH 3"}));
    const std::string svg = render_svg_chart(spec);
    const XmlCheck xml = check_xml(svg);
    ASSERT_TRUE(xml.ok) << xml.error;
    for (const char* label : {"SH 0", "SH 1", "SH 2", "SH 3"}) EXPECT_TRUE(has_text(svg, label)) << label;
    EXPECT_EQ(count(svg, "<polyline"), 1u + 1u + 1u);  // the third breaks: {25} alone, {26, 26.1}
    EXPECT_EQ(count(svg, "class=\"marker\""), 4u + 4u + 3u);
    // Category i sits at the same x for every item.
    const auto p = circle_markers(svg);
    ASSERT_EQ(p.size(), 11u);
    EXPECT_DOUBLE_EQ(p[0].first, p[4].first);
    EXPECT_DOUBLE_EQ(p[3].first, p[7].first);
}

TEST(PairedChart, TakesItemNamesAndRejectsMismatches) {
    const ChartSpec spec = paired_chart("t", "y", {"a", "b"}, {{1, 2}, {3, 4}}, {"garden", "bicycle"});
    EXPECT_EQ(spec.series[1].name, "bicycle");
    EXPECT_THROW(paired_chart("t", "y", {"a", "b"}, {{1, 2}, {3}}), std::invalid_argument);
    EXPECT_THROW(paired_chart("t", "y", {"a", "b"}, {{1, 2}}, {"one", "two"}), std::invalid_argument);
}

TEST(WriteSvgChart, WritesTheFileAndRefusesToReplaceItUnlessAsked) {
    const auto dir = std::filesystem::temp_directory_path() / ("vksplat_chart_test_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const auto path = dir / "chart.svg";
    std::filesystem::remove(path);
    const ChartSpec spec = three_series();
    write_svg_chart(path, spec, io::WriteMode::refuse_existing);
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str(), render_svg_chart(spec));
    EXPECT_THROW(write_svg_chart(path, spec, io::WriteMode::refuse_existing), InputError);
    ChartSpec other = spec;
    other.title = "replaced";
    write_svg_chart(path, other, io::WriteMode::overwrite, 800, 500);
    std::ifstream again(path);
    std::stringstream replaced;
    replaced << again.rdbuf();
    EXPECT_EQ(replaced.str(), render_svg_chart(other, 800, 500));
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace vksplat::report
