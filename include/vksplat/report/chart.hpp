#pragma once
// Line charts as standalone SVG files: size or speed against accuracy, per-view lines across
// settings. The SVG needs no scripts, fonts or styles from outside, so a browser, an <img> tag or
// an image viewer shows it as it is.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "vksplat/io/write_mode.hpp"

namespace vksplat::report {

// One line. x and y must have the same length (render_svg_chart throws std::invalid_argument
// otherwise). Points are joined in the order given; a point whose x or y is NaN or infinite (or
// whose x is not positive on a log axis) is skipped and breaks the line there, leaving a gap.
struct Series {
    std::string name;  // shown in the legend; an empty name leaves the series out of the legend
    std::vector<double> x, y;
    // The spread of each x, e.g. the fastest and slowest of repeated timings: empty, or as long as x
    // (else render_svg_chart throws std::invalid_argument). Each drawable point with a finite
    // x_low <= x <= x_high (positive on a log axis) gets a horizontal bar with end caps from x_low to
    // x_high, of class "spread"; the x axis widens to hold the bars.
    std::vector<double> x_low = {}, x_high = {};
};

struct ChartSpec {
    std::string title, x_label, y_label;
    std::vector<Series> series;
    bool log_x = false;  // logarithmic x axis, ticked at decades (and 2, 5 within short ranges)
    // Fixed ends of the y axis; when absent, the axis spans the data and the reference lines,
    // widened to the nearest ticks. A point outside a fixed range is drawn at the edge it lies
    // beyond as a triangle pointing off the plot (class "off-scale", points at one x stacked inward)
    // with its value beside it, and the legend says so; its lines run on to the edge and are cut.
    std::optional<double> y_min, y_max;
    // Horizontal dashed lines with a label, e.g. {31.2, "unpruned"}.
    std::vector<std::pair<double, std::string>> reference_lines;
    // Categories on the x axis: when not empty, tick i sits at x = i with this label, for
    // i = 0 .. size - 1, and log_x is ignored. See paired_chart.
    std::vector<std::string> x_tick_labels;
};

// The chart as an SVG document: title, axes with "nice" ticks (steps of 1, 2 or 5 times a power of
// ten), grid lines, axis labels, one colour-blind-safe colour (Okabe-Ito) per series, a marker at
// each point, a legend, and the reference lines. Each series is a <g class="series"> holding one
// <polyline> per unbroken run of two or more points and one element of class "marker" per
// drawable point. A chart with no drawable point still draws its axes and says "no data".
// All text is escaped for XML. Throws std::invalid_argument for a size below 200 x 150 or a series
// whose x and y differ in length.
std::string render_svg_chart(const ChartSpec& spec, int width = 720, int height = 440);

// Writes render_svg_chart(spec, width, height) to `path` through io::write_file_atomically.
void write_svg_chart(const std::filesystem::path& path, const ChartSpec& spec, io::WriteMode mode,
                     int width = 720, int height = 440);

// A chart of one line per item across categories, e.g. PSNR of each test view (item) at SH degree
// 0, 1, 2, 3 (categories): values_per_item[i][c] is item i's value in category c (NaN for none).
// Items are named item_names[i] when given (the list must then have one name per item), else
// "view 1", "view 2", ... Throws std::invalid_argument when an item's value count differs from the
// number of categories.
ChartSpec paired_chart(std::string title, std::string y_label, std::vector<std::string> categories,
                       std::vector<std::vector<double>> values_per_item,
                       std::vector<std::string> item_names = {});

// The tick values the charts use, exposed for tests and for callers that lay out their own axes.
// nice_ticks: multiples of a step of 1, 2 or 5 times a power of ten that cover [lo, hi] — the first
// tick is <= lo and the last >= hi — with about `target` intervals (at least 2 ticks). lo == hi is
// widened around the value first. Throws std::invalid_argument for non-finite bounds or lo > hi.
std::vector<double> nice_ticks(double lo, double hi, int target = 5);
// log_ticks: for 0 < lo <= hi, the powers of ten from the one at or below lo to the one at or above
// hi. When that spans fewer than three decades, 2 and 5 times each power are ticks too, and the list
// runs only from the last tick at or below lo to the first at or above hi (at least two ticks):
// (2e5, 9e5) -> {2e5, 5e5, 1e6}.
// Throws std::invalid_argument unless 0 < lo <= hi, both finite.
std::vector<double> log_ticks(double lo, double hi);
// Labels for ticks from nice_ticks (log = false) or log_ticks (log = true), as the charts print
// them: as few decimals as tell the ticks apart, trailing zeros dropped, and k / M / G suffixes for
// large values (linear: when the largest tick is 10 000 or more, for the whole axis; log: each
// tick from 1000 up), e.g. {0, 500000, 1000000} -> {"0", "0.5M", "1M"}, {1e2, 1e3} -> {"100", "1k"}.
std::vector<std::string> tick_labels(const std::vector<double>& ticks, bool log = false);

// Text made safe for XML and HTML, in element content and in quoted attributes alike: & < > " '
// become entities, and the control characters XML 1.0 forbids (all below U+0020 but tab, line feed
// and carriage return) are dropped. Other bytes, UTF-8 included, pass through.
std::string xml_escape(std::string_view text);

}  // namespace vksplat::report
