#include "vksplat/report/chart.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <system_error>

namespace vksplat::report {
namespace {

// Okabe & Ito (2008), "Color Universal Design": distinguishable under every common colour-vision
// deficiency. Yellow comes last because it is faint on white.
constexpr std::array<const char*, 8> kPalette = {"#0072B2", "#E69F00", "#009E73", "#D55E00",
                                                 "#CC79A7", "#56B4E9", "#000000", "#F0E442"};
enum class Marker { circle, square, triangle, diamond };
constexpr std::array<Marker, 4> kMarkers = {Marker::circle, Marker::square, Marker::triangle, Marker::diamond};

constexpr const char* kFontFamily = "DejaVu Sans, Helvetica, Arial, sans-serif";
constexpr double kTickFont = 12.0;
constexpr double kLabelFont = 13.0;
constexpr double kTitleFont = 16.0;
constexpr double kLegendFont = 12.0;
constexpr double kMarkerRadius = 3.5;
// Average advance of a character as a fraction of the font size: wide enough for DejaVu Sans, the
// widest of the fonts named, so that laid-out text does not collide.
constexpr double kCharWidth = 0.62;

double text_width(const std::string& text, double font_size) {
    // Count UTF-8 code points, not bytes.
    size_t chars = 0;
    for (unsigned char c : text)
        if ((c & 0xC0) != 0x80) ++chars;
    return static_cast<double>(chars) * font_size * kCharWidth;
}

// Coordinates with two decimals, independent of the C locale.
std::string num(double v) {
    if (std::abs(v) < 0.005) v = 0.0;  // no "-0.00"
    char buf[512];
    const auto r = std::to_chars(buf, buf + sizeof(buf), v, std::chars_format::fixed, 2);
    return std::string(buf, r.ptr);
}

std::string fixed(double v, int decimals) {
    char buf[512];  // room for 1e308 with 12 decimals
    const auto r = std::to_chars(buf, buf + sizeof(buf), v, std::chars_format::fixed, decimals);
    std::string s(buf, r.ptr);
    if (s.find('.') != std::string::npos) {
        while (s.back() == '0') s.pop_back();
        if (s.back() == '.') s.pop_back();
    }
    if (s == "-0") s = "0";
    return s;
}

// 10^k, correctly rounded for negative k too (10^-3 is 1 / 1000, not 0.1 * 0.1 * 0.1).
// For messages: shortest round-trip form.
std::string general(double v) {
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof(buf), v);
    return std::string(buf, r.ptr);
}

double pow10(int k) { return std::pow(10.0, k); }

// m * 10^k * i, computed so that decimal tick values come out as the nearest double.
double tick_value(long long i, int m, int k) {
    const double count = static_cast<double>(i) * m;
    return k >= 0 ? count * pow10(k) : count / pow10(-k);
}

int floor_log10(double v) { return static_cast<int>(std::floor(std::log10(v) + 1e-9)); }
int ceil_log10(double v) { return static_cast<int>(std::ceil(std::log10(v) - 1e-9)); }

struct Axis {
    double lo = 0.0, hi = 1.0;  // the domain mapped onto the plot
    bool log = false;
    std::vector<double> ticks;
    std::vector<std::string> labels;

    // 0 at lo, 1 at hi.
    double fraction(double v) const {
        if (log) return (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo));
        return (v - lo) / (hi - lo);
    }
};

bool drawable(double x, double y, bool log_x) {
    return std::isfinite(x) && std::isfinite(y) && (!log_x || x > 0.0);
}

// Point i of s has a spread bar to draw (Series::x_low, x_high).
bool has_spread(const Series& s, size_t i, bool log_x) {
    if (s.x_low.empty()) return false;
    const double lo = s.x_low[i], hi = s.x_high[i];
    return std::isfinite(lo) && std::isfinite(hi) && lo <= s.x[i] && s.x[i] <= hi && (!log_x || lo > 0.0);
}

// Where a point lies against a fixed y range (ChartSpec::y_min, y_max).
enum class Scale { inside, below, above };

// What the legend says of off-scale markers.
constexpr const char* kOffScaleNote = "off scale (value shown)";
constexpr const char* kOffScaleColour = "#555555";

struct Extent {
    double lo = std::numeric_limits<double>::infinity();
    double hi = -std::numeric_limits<double>::infinity();
    void add(double v) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    bool empty() const { return lo > hi; }
};

Axis make_linear_axis(double lo, double hi, std::optional<double> fixed_lo, std::optional<double> fixed_hi) {
    Axis axis;
    if (fixed_lo) lo = *fixed_lo;
    if (fixed_hi) hi = *fixed_hi;
    if (fixed_lo && fixed_hi && !(*fixed_lo < *fixed_hi))
        throw std::invalid_argument("chart: y_min " + general(*fixed_lo) + " is not below y_max " +
                                    general(*fixed_hi));
    if (lo > hi) {  // one fixed end on the wrong side of the data: keep the fixed end
        const double pad = lo == 0.0 ? 1.0 : std::abs(fixed_lo ? lo : hi) * 0.1;
        if (fixed_lo) hi = lo + pad;
        else lo = hi - pad;
    }
    const std::vector<double> ticks = nice_ticks(lo, hi);
    axis.lo = fixed_lo ? *fixed_lo : ticks.front();
    axis.hi = fixed_hi ? *fixed_hi : ticks.back();
    const double eps = (axis.hi - axis.lo) * 1e-9;
    for (double t : ticks)
        if (t >= axis.lo - eps && t <= axis.hi + eps) axis.ticks.push_back(t);
    axis.labels = tick_labels(axis.ticks, false);
    return axis;
}

Axis make_log_axis(double lo, double hi) {
    Axis axis;
    axis.log = true;
    axis.ticks = log_ticks(lo, hi);
    axis.lo = axis.ticks.front();
    axis.hi = axis.ticks.back();
    axis.labels = tick_labels(axis.ticks, true);
    return axis;
}

class SvgWriter {
public:
    void raw(const std::string& s) { out_ += s; }
    void text(double x, double y, const std::string& content, double size, const char* anchor,
              const std::string& extra = "") {
        out_ += "<text x=\"" + num(x) + "\" y=\"" + num(y) + "\" font-size=\"" + num(size) +
                "\" text-anchor=\"" + anchor + "\"" + (extra.empty() ? "" : " " + extra) + ">" +
                xml_escape(content) + "</text>\n";
    }
    void line(double x1, double y1, double x2, double y2, const std::string& style) {
        out_ += "<line x1=\"" + num(x1) + "\" y1=\"" + num(y1) + "\" x2=\"" + num(x2) + "\" y2=\"" + num(y2) +
                "\" " + style + "/>\n";
    }
    void marker(Marker shape, double x, double y, const char* colour, const char* css_class) {
        const double r = kMarkerRadius;
        const std::string head = std::string("class=\"") + css_class + "\" fill=\"" + colour + "\" ";
        switch (shape) {
            case Marker::circle:
                out_ += "<circle " + head + "cx=\"" + num(x) + "\" cy=\"" + num(y) + "\" r=\"" + num(r) + "\"/>\n";
                break;
            case Marker::square: {
                const double s = r * 0.9;
                out_ += "<rect " + head + "x=\"" + num(x - s) + "\" y=\"" + num(y - s) + "\" width=\"" +
                        num(2 * s) + "\" height=\"" + num(2 * s) + "\"/>\n";
                break;
            }
            case Marker::triangle: {
                const double s = r * 1.25;
                out_ += "<path " + head + "d=\"M" + num(x) + " " + num(y - s) + "L" + num(x + s) + " " +
                        num(y + 0.8 * s) + "L" + num(x - s) + " " + num(y + 0.8 * s) + "Z\"/>\n";
                break;
            }
            case Marker::diamond: {
                const double s = r * 1.3;
                out_ += "<path " + head + "d=\"M" + num(x) + " " + num(y - s) + "L" + num(x + s) + " " + num(y) +
                        "L" + num(x) + " " + num(y + s) + "L" + num(x - s) + " " + num(y) + "Z\"/>\n";
                break;
            }
        }
    }
    // A triangle pointing off the plot: down for a value below the axis, up for one above.
    void off_scale_marker(double x, double y, bool below, const char* colour, const char* css_class) {
        const double s = kMarkerRadius * 1.5, tip = below ? s : -s;
        out_ += std::string("<path class=\"") + css_class + "\" fill=\"" + colour + "\" d=\"M" + num(x - s) + " " +
                num(y - 0.6 * tip) + "L" + num(x + s) + " " + num(y - 0.6 * tip) + "L" + num(x) + " " + num(y + tip) +
                "Z\"/>\n";
    }
    std::string take() { return std::move(out_); }

private:
    std::string out_;
};

// A name cut to fit `max_width` pixels, with an ellipsis where it was cut.
std::string fit_text(const std::string& text, double font_size, double max_width) {
    if (text_width(text, font_size) <= max_width) return text;
    const std::string ellipsis = "\xE2\x80\xA6";  // U+2026
    std::string cut;
    size_t i = 0;
    while (i < text.size()) {
        size_t j = i + 1;  // whole UTF-8 sequences only
        while (j < text.size() && (static_cast<unsigned char>(text[j]) & 0xC0) == 0x80) ++j;
        std::string longer = cut + text.substr(i, j - i);
        if (text_width(longer + ellipsis, font_size) > max_width) break;
        cut = std::move(longer);
        i = j;
    }
    return cut + ellipsis;
}

}  // namespace

std::string xml_escape(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (char ch : text) {
        switch (ch) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&#39;"; break;
            default:
                if (static_cast<unsigned char>(ch) < 0x20 && ch != '\t' && ch != '\n' && ch != '\r') break;
                out += ch;
        }
    }
    return out;
}

std::vector<double> nice_ticks(double lo, double hi, int target) {
    if (!std::isfinite(lo) || !std::isfinite(hi) || lo > hi)
        throw std::invalid_argument("nice_ticks: range [" + general(lo) + ", " + general(hi) +
                                    "] is not finite and ordered");
    if (!std::isfinite(hi - lo))
        throw std::invalid_argument("nice_ticks: range [" + general(lo) + ", " + general(hi) + "] is too wide");
    target = std::max(target, 1);
    if (lo == hi) {
        const double pad = lo == 0.0 ? 1.0 : std::abs(lo) * 0.1;
        lo -= pad;
        hi += pad;
    }
    const double raw = (hi - lo) / target;
    int k = static_cast<int>(std::floor(std::log10(raw)));
    const double f = raw / pow10(k);
    int m = 10;
    if (f < 1.5) m = 1;
    else if (f < 3.5) m = 2;
    else if (f < 7.5) m = 5;
    if (m == 10) {
        m = 1;
        ++k;
    }
    const double step = tick_value(1, m, k);
    auto i0 = static_cast<long long>(std::floor(lo / step + 1e-9));
    auto i1 = static_cast<long long>(std::ceil(hi / step - 1e-9));
    if (i1 <= i0) i1 = i0 + 1;
    std::vector<double> ticks;
    for (long long i = i0; i <= i1; ++i) ticks.push_back(tick_value(i, m, k));
    return ticks;
}

std::vector<double> log_ticks(double lo, double hi) {
    if (!(lo > 0.0) || !std::isfinite(lo) || !std::isfinite(hi) || lo > hi)
        throw std::invalid_argument("log_ticks: range [" + general(lo) + ", " + general(hi) +
                                    "] is not positive, finite and ordered");
    const int k0 = floor_log10(lo);
    const int k1 = std::max(ceil_log10(hi), k0 + 1);
    std::vector<double> ticks;
    const bool fine = k1 - k0 < 3;
    for (int k = k0; k <= k1; ++k) {
        ticks.push_back(tick_value(1, 1, k));
        if (fine && k < k1) {
            ticks.push_back(tick_value(2, 1, k));
            ticks.push_back(tick_value(5, 1, k));
        }
    }
    if (!fine) return ticks;
    // Keep the axis tight: from the last tick at or below lo to the first at or above hi.
    size_t first = 0, last = ticks.size() - 1;
    while (first + 1 < ticks.size() && ticks[first + 1] <= lo * (1 + 1e-9)) ++first;
    while (last > 0 && ticks[last - 1] >= hi * (1 - 1e-9)) --last;
    if (last <= first) last = first + 1;
    return {ticks.begin() + static_cast<std::ptrdiff_t>(first), ticks.begin() + static_cast<std::ptrdiff_t>(last) + 1};
}

std::vector<std::string> tick_labels(const std::vector<double>& ticks, bool log) {
    static constexpr std::array<std::pair<double, const char*>, 3> kSuffixes = {
        {{1e9, "G"}, {1e6, "M"}, {1e3, "k"}}};
    std::vector<std::string> labels;
    if (log) {
        for (double t : ticks) {
            double scaled = t;
            const char* suffix = "";
            for (const auto& [div, s] : kSuffixes)
                if (std::abs(t) >= div * (1 - 1e-9)) {
                    scaled = t / div;
                    suffix = s;
                    break;
                }
            const int decimals = scaled == 0.0 ? 0 : std::max(0, -floor_log10(std::abs(scaled)));
            labels.push_back(fixed(scaled, decimals) + suffix);
        }
        return labels;
    }
    double largest = 0.0;
    double step = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < ticks.size(); ++i) {
        largest = std::max(largest, std::abs(ticks[i]));
        if (i > 0 && ticks[i] != ticks[i - 1]) step = std::min(step, std::abs(ticks[i] - ticks[i - 1]));
    }
    double div = 1.0;
    const char* suffix = "";
    if (largest >= 1e4)
        for (const auto& [d, s] : kSuffixes)
            if (largest >= d) {
                div = d;
                suffix = s;
                break;
            }
    int decimals = 0;
    if (std::isfinite(step)) decimals = std::clamp(-floor_log10(step / div), 0, 12);
    else if (largest > 0.0) decimals = std::clamp(3 - floor_log10(largest / div), 0, 12);
    for (double t : ticks) {
        std::string s = fixed(t / div, decimals);
        labels.push_back(s == "0" ? s : s + suffix);
    }
    return labels;
}

std::string render_svg_chart(const ChartSpec& spec, int width, int height) {
    if (width < 200 || height < 150)
        throw std::invalid_argument("render_svg_chart: size " + std::to_string(width) + " x " +
                                    std::to_string(height) + " is below 200 x 150");
    for (const Series& s : spec.series)
        if (s.x.size() != s.y.size())
            throw std::invalid_argument("render_svg_chart: series '" + s.name + "' has " +
                                        std::to_string(s.x.size()) + " x values but " +
                                        std::to_string(s.y.size()) + " y values");
    for (const Series& s : spec.series)
        if ((!s.x_low.empty() && s.x_low.size() != s.x.size()) || (!s.x_high.empty() && s.x_high.size() != s.x.size()) ||
            s.x_low.empty() != s.x_high.empty())
            throw std::invalid_argument("render_svg_chart: series '" + s.name + "' has " +
                                        std::to_string(s.x_low.size()) + " x_low and " +
                                        std::to_string(s.x_high.size()) + " x_high values for " +
                                        std::to_string(s.x.size()) + " points");
    const bool categories = !spec.x_tick_labels.empty();
    const bool log_x = spec.log_x && !categories;

    // Data extents over drawable points.
    Extent ex, ey;
    size_t drawable_points = 0;
    for (const Series& s : spec.series)
        for (size_t i = 0; i < s.x.size(); ++i)
            if (drawable(s.x[i], s.y[i], log_x)) {
                ex.add(s.x[i]);
                ey.add(s.y[i]);
                ++drawable_points;
                if (has_spread(s, i, log_x)) {
                    ex.add(s.x_low[i]);
                    ex.add(s.x_high[i]);
                }
            }
    for (const auto& [y, label] : spec.reference_lines)
        if (std::isfinite(y)) ey.add(y);

    Axis x_axis;
    if (categories) {
        const auto n = static_cast<double>(spec.x_tick_labels.size());
        x_axis.lo = -0.35;
        x_axis.hi = n - 1 + 0.35;
        for (size_t i = 0; i < spec.x_tick_labels.size(); ++i) x_axis.ticks.push_back(static_cast<double>(i));
        x_axis.labels = spec.x_tick_labels;
    } else if (log_x) {
        x_axis = ex.empty() ? make_log_axis(1.0, 10.0) : make_log_axis(ex.lo, ex.hi);
    } else {
        x_axis = ex.empty() ? make_linear_axis(0.0, 1.0, {}, {}) : make_linear_axis(ex.lo, ex.hi, {}, {});
    }
    const Axis y_axis = ey.empty() ? make_linear_axis(0.0, 1.0, spec.y_min, spec.y_max)
                                   : make_linear_axis(ey.lo, ey.hi, spec.y_min, spec.y_max);

    // Points beyond a fixed y range; the legend explains their markers.
    const double y_eps = (y_axis.hi - y_axis.lo) * 1e-9;
    const auto scale_of = [&](double y) {
        return y < y_axis.lo - y_eps ? Scale::below : y > y_axis.hi + y_eps ? Scale::above : Scale::inside;
    };
    bool any_off_scale = false;
    for (const Series& s : spec.series)
        for (size_t i = 0; i < s.x.size(); ++i)
            any_off_scale |= drawable(s.x[i], s.y[i], log_x) && scale_of(s.y[i]) != Scale::inside;

    // Legend entries: named series only, then the off-scale note (kNote) where there are such points.
    constexpr size_t kNote = std::numeric_limits<size_t>::max();
    std::vector<size_t> legend_entries;
    double legend_text_width = 0.0;
    for (size_t i = 0; i < spec.series.size(); ++i)
        if (!spec.series[i].name.empty()) {
            legend_entries.push_back(i);
            legend_text_width = std::max(legend_text_width, text_width(spec.series[i].name, kLegendFont));
        }
    if (any_off_scale) {
        legend_entries.push_back(kNote);
        legend_text_width = std::max(legend_text_width, text_width(kOffScaleNote, kLegendFont));
    }

    // Layout.
    const double W = width, H = height;
    const double top = spec.title.empty() ? 16.0 : 46.0;
    const double bottom = H - (spec.x_label.empty() ? 34.0 : 54.0);
    double widest_y_label = 0.0;
    for (const std::string& l : y_axis.labels) widest_y_label = std::max(widest_y_label, text_width(l, kTickFont));
    const double left = (spec.y_label.empty() ? 10.0 : 32.0) + widest_y_label + 10.0;
    constexpr double kLegendRow = 20.0, kLegendSample = 26.0, kLegendPad = 10.0;
    const double row_capacity = std::max(1.0, std::floor((bottom - top) / kLegendRow));
    const auto legend_columns = legend_entries.empty()
                                    ? 0
                                    : static_cast<int>(std::ceil(legend_entries.size() / row_capacity));
    const auto legend_rows = legend_columns == 0
                                 ? 0
                                 : static_cast<int>(std::ceil(legend_entries.size() / double(legend_columns)));
    double column_width = kLegendSample + 6.0 + legend_text_width + 12.0;
    const double max_legend_width = 0.4 * W;
    if (legend_columns * column_width > max_legend_width) column_width = max_legend_width / legend_columns;
    const double legend_width = legend_columns * column_width;
    const double right = W - 16.0 - (legend_columns > 0 ? legend_width + kLegendPad : 0.0);
    const double plot_w = std::max(right - left, 10.0), plot_h = std::max(bottom - top, 10.0);

    // A small margin inside the axes, so that points at the ends of a range do not sit on an axis
    // line (categories have theirs already).
    const double x_inset = categories ? 0.0 : 8.0, y_inset = 8.0;
    auto px = [&](double x) { return left + x_inset + x_axis.fraction(x) * (plot_w - 2 * x_inset); };
    auto py = [&](double y) { return bottom - y_inset - y_axis.fraction(y) * (plot_h - 2 * y_inset); };

    SvgWriter svg;
    svg.raw("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    svg.raw("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(width) + "\" height=\"" +
            std::to_string(height) + "\" viewBox=\"0 0 " + std::to_string(width) + " " + std::to_string(height) +
            "\" font-family=\"" + kFontFamily + "\" role=\"img\">\n");
    svg.raw("<title>" + xml_escape(spec.title.empty() ? "chart" : spec.title) + "</title>\n");
    svg.raw("<rect x=\"0\" y=\"0\" width=\"" + std::to_string(width) + "\" height=\"" + std::to_string(height) +
            "\" fill=\"#ffffff\"/>\n");
    // Markers may sit on the plot's edge; let them show whole, but clip what lies beyond.
    const double m = kMarkerRadius * 1.5;
    svg.raw("<defs><clipPath id=\"plot-area\"><rect x=\"" + num(left - m) + "\" y=\"" + num(top - m) +
            "\" width=\"" + num(plot_w + 2 * m) + "\" height=\"" + num(plot_h + 2 * m) +
            "\"/></clipPath></defs>\n");

    // Grid and ticks.
    svg.raw("<g class=\"grid\" stroke=\"#e6e6e6\" stroke-width=\"1\">\n");
    for (double t : y_axis.ticks) svg.line(left, py(t), left + plot_w, py(t), "");
    for (double t : x_axis.ticks) svg.line(px(t), top, px(t), bottom, "");
    svg.raw("</g>\n");
    svg.raw("<g class=\"axes\" stroke=\"#333333\" stroke-width=\"1\">\n");
    svg.line(left, bottom, left + plot_w, bottom, "");
    svg.line(left, top, left, bottom, "");
    for (double t : y_axis.ticks) svg.line(left - 5, py(t), left, py(t), "");
    for (double t : x_axis.ticks) svg.line(px(t), bottom, px(t), bottom + 5, "");
    svg.raw("</g>\n");
    svg.raw("<g class=\"tick-labels\" fill=\"#333333\">\n");
    for (size_t i = 0; i < y_axis.ticks.size(); ++i)
        svg.text(left - 8, py(y_axis.ticks[i]) + kTickFont * 0.35, y_axis.labels[i], kTickFont, "end");
    for (size_t i = 0; i < x_axis.ticks.size(); ++i)
        svg.text(px(x_axis.ticks[i]), bottom + 8 + kTickFont, x_axis.labels[i], kTickFont, "middle");
    svg.raw("</g>\n");

    // Title and axis labels.
    if (!spec.title.empty())
        svg.text(left + plot_w / 2, 28, spec.title, kTitleFont, "middle", "font-weight=\"bold\" fill=\"#111111\"");
    if (!spec.x_label.empty())
        svg.text(left + plot_w / 2, H - 14, spec.x_label, kLabelFont, "middle", "fill=\"#222222\"");
    if (!spec.y_label.empty()) {
        const double cx = 18, cy = top + plot_h / 2;
        svg.text(cx, cy, spec.y_label, kLabelFont, "middle",
                 "fill=\"#222222\" transform=\"rotate(-90 " + num(cx) + " " + num(cy) + ")\"");
    }

    // Reference lines, under the data.
    for (const auto& [y, label] : spec.reference_lines) {
        if (!std::isfinite(y) || y < y_axis.lo || y > y_axis.hi) continue;
        svg.raw("<g class=\"reference\">\n");
        svg.line(left, py(y), left + plot_w, py(y),
                 "stroke=\"#555555\" stroke-width=\"1.25\" stroke-dasharray=\"6 4\"");
        if (!label.empty())
            svg.text(left + plot_w - 4, py(y) - 5, label, 11.0, "end",
                     "fill=\"#444444\" stroke=\"#ffffff\" stroke-width=\"3\" paint-order=\"stroke\"");
        svg.raw("</g>\n");
    }

    // The series. Off-scale markers stack per edge and x (rounded to 6 px) across the series.
    std::map<std::pair<bool, long>, int> off_scale_stacks;
    for (size_t si = 0; si < spec.series.size(); ++si) {
        const Series& s = spec.series[si];
        const char* colour = kPalette[si % kPalette.size()];
        const Marker shape = kMarkers[(si / kPalette.size()) % kMarkers.size()];
        svg.raw("<g class=\"series\" data-name=\"" + xml_escape(s.name) + "\" clip-path=\"url(#plot-area)\">\n");
        // Unbroken runs of drawable points.
        std::vector<std::pair<double, double>> run;
        auto flush = [&] {
            if (run.size() >= 2) {
                std::string points;
                for (const auto& [x, y] : run) {
                    if (!points.empty()) points += ' ';
                    points += num(x);
                    points += ',';
                    points += num(y);
                }
                svg.raw("<polyline fill=\"none\" stroke=\"" + std::string(colour) +
                        "\" stroke-width=\"2\" stroke-linejoin=\"round\" stroke-linecap=\"round\" points=\"" +
                        points + "\"/>\n");
            }
            run.clear();
        };
        for (size_t i = 0; i < s.x.size(); ++i) {
            if (drawable(s.x[i], s.y[i], log_x)) run.emplace_back(px(s.x[i]), py(s.y[i]));
            else flush();
        }
        flush();
        for (size_t i = 0; i < s.x.size(); ++i) {
            if (!drawable(s.x[i], s.y[i], log_x) || !has_spread(s, i, log_x) || scale_of(s.y[i]) != Scale::inside)
                continue;
            const double y = py(s.y[i]), x0 = px(s.x_low[i]), x1 = px(s.x_high[i]), cap = kMarkerRadius * 1.2;
            svg.raw("<path class=\"spread\" fill=\"none\" stroke=\"" + std::string(colour) +
                    "\" stroke-width=\"1.25\" d=\"M" + num(x0) + " " + num(y) + "H" + num(x1) + "M" + num(x0) + " " +
                    num(y - cap) + "V" + num(y + cap) + "M" + num(x1) + " " + num(y - cap) + "V" + num(y + cap) +
                    "\"/>\n");
        }
        svg.raw("<g stroke=\"#ffffff\" stroke-width=\"1\">\n");
        for (size_t i = 0; i < s.x.size(); ++i) {
            if (!drawable(s.x[i], s.y[i], log_x)) continue;
            const Scale where = scale_of(s.y[i]);
            if (where == Scale::inside) {
                svg.marker(shape, px(s.x[i]), py(s.y[i]), colour, "marker");
                continue;
            }
            // At the edge, stacked inward past the markers already at (about) this x.
            const double x = px(s.x[i]);
            const bool below = where == Scale::below;
            int& stacked = off_scale_stacks[{below, std::lround(x / 6.0)}];
            const double step = kMarkerRadius * 3.6;
            const double y = below ? py(y_axis.lo) - stacked * step : py(y_axis.hi) + stacked * step;
            ++stacked;
            svg.off_scale_marker(x, y, below, colour, "off-scale");
            char value[32];
            const auto r = std::to_chars(value, value + sizeof(value), s.y[i], std::chars_format::general, 3);
            svg.text(x + kMarkerRadius * 2, y + kTickFont * 0.3, std::string(value, r.ptr), 10.0, "start",
                     std::string("class=\"off-scale-value\" fill=\"") + colour +
                         "\" stroke=\"#ffffff\" stroke-width=\"3\" paint-order=\"stroke\"");
        }
        svg.raw("</g>\n</g>\n");
    }

    if (drawable_points == 0)
        svg.text(left + plot_w / 2, top + plot_h / 2, "no data", 14.0, "middle", "fill=\"#777777\"");

    // Legend, to the right of the plot.
    if (legend_columns > 0) {
        svg.raw("<g class=\"legend\">\n");
        const double x0 = right + kLegendPad;
        const double y0 = top + 4;
        for (size_t e = 0; e < legend_entries.size(); ++e) {
            const size_t si = legend_entries[e];
            const auto col = static_cast<double>(e / legend_rows);
            const auto row = static_cast<double>(e % legend_rows);
            const double x = x0 + col * column_width, y = y0 + row * kLegendRow + kLegendRow / 2;
            if (si == kNote) {
                svg.off_scale_marker(x + kLegendSample / 2, y, true, kOffScaleColour, "legend-off-scale");
                svg.text(x + kLegendSample + 6, y + kLegendFont * 0.35,
                         fit_text(kOffScaleNote, kLegendFont, column_width - kLegendSample - 6.0 - 8.0), kLegendFont,
                         "start", "fill=\"#222222\"");
                continue;
            }
            const char* colour = kPalette[si % kPalette.size()];
            svg.line(x, y, x + kLegendSample, y,
                     std::string("stroke=\"") + colour + "\" stroke-width=\"2\" stroke-linecap=\"round\"");
            svg.raw("<g stroke=\"#ffffff\" stroke-width=\"1\">\n");
            svg.marker(kMarkers[(si / kPalette.size()) % kMarkers.size()], x + kLegendSample / 2, y, colour,
                       "legend-marker");
            svg.raw("</g>\n");
            const std::string name =
                fit_text(spec.series[si].name, kLegendFont, column_width - kLegendSample - 6.0 - 8.0);
            svg.text(x + kLegendSample + 6, y + kLegendFont * 0.35, name, kLegendFont, "start", "fill=\"#222222\"");
        }
        svg.raw("</g>\n");
    }
    svg.raw("</svg>\n");
    return svg.take();
}

void write_svg_chart(const std::filesystem::path& path, const ChartSpec& spec, io::WriteMode mode, int width,
                     int height) {
    const std::string svg = render_svg_chart(spec, width, height);
    io::write_file_atomically(path, mode, [&](std::ostream& out) { out << svg; });
}

ChartSpec paired_chart(std::string title, std::string y_label, std::vector<std::string> categories,
                       std::vector<std::vector<double>> values_per_item, std::vector<std::string> item_names) {
    if (!item_names.empty() && item_names.size() != values_per_item.size())
        throw std::invalid_argument("paired_chart: " + std::to_string(item_names.size()) + " item names for " +
                                    std::to_string(values_per_item.size()) + " items");
    ChartSpec spec;
    spec.title = std::move(title);
    spec.y_label = std::move(y_label);
    for (size_t i = 0; i < values_per_item.size(); ++i) {
        if (values_per_item[i].size() != categories.size())
            throw std::invalid_argument("paired_chart: item " + std::to_string(i) + " has " +
                                        std::to_string(values_per_item[i].size()) + " values for " +
                                        std::to_string(categories.size()) + " categories");
        Series s;
        s.name = item_names.empty() ? "view " + std::to_string(i + 1) : std::move(item_names[i]);
        for (size_t c = 0; c < categories.size(); ++c) s.x.push_back(static_cast<double>(c));
        s.y = std::move(values_per_item[i]);
        spec.series.push_back(std::move(s));
    }
    spec.x_tick_labels = std::move(categories);
    return spec;
}

}  // namespace vksplat::report
