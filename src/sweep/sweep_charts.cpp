// The sweep's charts as SVG files (report::write_svg_chart): quality against the dropped fraction,
// the time per frame and the size, one line per method; the best method's quality against its
// file's size in each format, pruned and re-fitted; per-view PSNR across SH degrees.
#include <cctype>
#include <cmath>
#include <cstdio>
#include <string>

#include "sweep_parts.hpp"
#include "vksplat/report/chart.hpp"

namespace vksplat::sweep::detail {
namespace {

namespace fs = std::filesystem;

// Charts this size sit two to a row in the report on a laptop screen.
constexpr int kWidth = 620, kHeight = 400;

// One series per method, in the rows' order, with x and y read from each of its rows.
template <typename X, typename Y>
std::vector<report::Series> per_method(const std::vector<SweepRow>& rows, X x, Y y) {
    std::vector<report::Series> series;
    for (const SweepRow& row : rows) {
        const std::string name(row.method);
        if (series.empty() || series.back().name != name) series.push_back({name, {}, {}});
        series.back().x.push_back(x(row));
        series.back().y.push_back(y(row));
    }
    return series;
}

std::string decimals(double value, int places) {
    char text[48];
    std::snprintf(text, sizeof(text), "%.*f", places, value);
    return text;
}

// "SPZ", "compressed PLY": a scene format (io::write_scene's name) as the charts say it.
std::string format_label(const std::string& format) {
    if (format == "compressed-ply") return "compressed PLY";
    if (format == "spz-v4") return "SPZ v4";
    if (format == "gltf") return "glTF";
    if (format == "splat") return "splat";
    std::string upper = format;
    for (char& c : upper) c = char(std::toupper(static_cast<unsigned char>(c)));
    return upper;
}

// The model's file in `format`, in megabytes (10^6 bytes); NaN (no point) when it was not sized so.
double file_megabytes(const ModelMeasure& measure, const std::string& format) {
    for (const auto& [name, bytes] : measure.file_bytes)
        if (name == format) return double(bytes) / 1e6;
    return std::nan("");
}

// PSNR against file size for `method` and its re-fitted rows, one line per format and each re-fitted
// one beside it: which format and whether to re-fit, at a glance.
report::ChartSpec size_by_format(const SweepResult& result, const std::vector<std::string>& formats,
                                 const std::string& method) {
    report::ChartSpec spec;
    spec.title = "PSNR against file size by format (" + method + ")";
    spec.x_label = "file size (MB; log scale)";
    spec.y_label = "PSNR (dB)";
    spec.log_x = true;
    for (const std::string& format : formats)
        for (const std::string& rows : {method, method + kRecoverSuffix}) {
            report::Series series{format_label(format) + (rows == method ? "" : " re-fitted"), {}, {}};
            for (const SweepRow& row : result.rows)
                if (row.method == rows) {
                    series.x.push_back(file_megabytes(row.measure, format));
                    series.y.push_back(row.measure.psnr);
                }
            if (!series.x.empty()) spec.series.push_back(std::move(series));
        }
    spec.reference_lines = {{result.unpruned.psnr, "unpruned " + decimals(result.unpruned.psnr, 2) + " dB"}};
    return spec;
}

report::ReportImage write_chart(const fs::path& out_dir, const std::string& file, const report::ChartSpec& spec,
                              const std::string& caption, io::WriteMode mode) {
    const std::string relative = "charts/" + file;
    report::write_svg_chart(out_dir / relative, spec, mode, kWidth, kHeight);
    return {relative, caption};
}

}  // namespace

SweepCharts write_sweep_charts(const fs::path& out_dir, const SweepResult& result, io::WriteMode mode) {
    const auto& rows = result.rows;
    const auto fraction = [](const SweepRow& r) { return r.fraction; };
    const auto psnr = [](const SweepRow& r) { return r.measure.psnr; };
    const std::pair<double, std::string> unpruned_psnr{result.unpruned.psnr,
                                                       "unpruned " + decimals(result.unpruned.psnr, 2) + " dB"};
    SweepCharts charts;

    report::ChartSpec spec;
    spec.title = "PSNR against the photos by dropped fraction";
    spec.x_label = "fraction of the Gaussians dropped";
    spec.y_label = "PSNR (dB)";
    spec.series = per_method(rows, fraction, psnr);
    spec.reference_lines = {unpruned_psnr};
    charts.sweep.push_back(write_chart(out_dir, "psnr_vs_fraction.svg", spec,
                                       "PSNR (mean over the test views) against the dropped fraction", mode));

    // The same, zoomed in where the targets lie (a loss of 0.1 dB at half, 1 dB at 80% dropped).
    spec.title = "PSNR change by dropped fraction (zoomed)";
    spec.y_label = "PSNR - unpruned PSNR (dB)";
    spec.series = per_method(rows, fraction, [](const SweepRow& r) { return r.delta_psnr; });
    spec.reference_lines = {{-0.1, "-0.1 dB"}, {-1.0, "-1 dB"}};
    spec.y_min = -2.0;
    spec.y_max = 0.5;
    charts.sweep.push_back(write_chart(out_dir, "delta_psnr_vs_fraction.svg", spec,
                                       "PSNR change against the dropped fraction, clipped to -2..0.5 dB", mode));
    spec.y_min.reset();
    spec.y_max.reset();

    spec.title = "SSIM against the photos by dropped fraction";
    spec.y_label = "SSIM";
    spec.series = per_method(rows, fraction, [](const SweepRow& r) { return r.measure.ssim; });
    spec.reference_lines = {{result.unpruned.ssim, "unpruned " + decimals(result.unpruned.ssim, 4)}};
    charts.sweep.push_back(write_chart(out_dir, "ssim_vs_fraction.svg", spec,
                                       "SSIM (mean over the test views) against the dropped fraction", mode));

    spec.title = "PSNR against time per frame";
    spec.x_label = "GPU time per frame (ms, median; log scale)";
    spec.y_label = "PSNR (dB)";
    spec.log_x = true;
    spec.series = per_method(rows, [](const SweepRow& r) { return r.measure.ms_per_frame; }, psnr);
    for (report::Series& series : spec.series)  // the timings' spread, row by row as per_method read them
        for (const SweepRow& r : rows)
            if (r.method == series.name) {
                series.x_low.push_back(r.measure.ms_min);
                series.x_high.push_back(r.measure.ms_max);
            }
    spec.reference_lines = {unpruned_psnr};
    charts.sweep.push_back(write_chart(out_dir, "psnr_vs_ms.svg", spec,
                                       "PSNR against GPU time per frame, bars from the fastest to the slowest frame "
                                       "(unpruned: " + decimals(result.unpruned.ms_per_frame, 2) + " ms, " +
                                           decimals(result.unpruned.ms_min, 2) + "-" +
                                           decimals(result.unpruned.ms_max, 2) + ")",
                                       mode));

    spec.title = "PSNR against size";
    spec.x_label = "size as INRIA PLY (MB; log scale)";
    spec.series = per_method(rows, [](const SweepRow& r) { return double(r.measure.bytes) / 1e6; }, psnr);
    charts.sweep.push_back(write_chart(out_dir, "psnr_vs_mb.svg", spec,
                                       "PSNR against megabytes (unpruned: " +
                                           decimals(double(result.unpruned.bytes) / 1e6, 2) + " MB)",
                                       mode));

    // Each size format: the best method by format first, then every method in each format.
    std::vector<std::string> formats;
    std::string unpruned_sizes;
    for (const auto& [format, bytes] : result.unpruned.file_bytes) {
        formats.push_back(format);
        unpruned_sizes += (unpruned_sizes.empty() ? "" : ", ") + format_label(format) + " " +
                          decimals(double(bytes) / 1e6, 2) + " MB";
    }
    if (!formats.empty())
        charts.sweep.push_back(write_chart(out_dir, "psnr_vs_mb_by_format.svg",
                                           size_by_format(result, formats, result.best_method),
                                           "PSNR against the file's megabytes in each format for the best method, " +
                                               result.best_method + ", and re-fitted where the sweep re-fitted "
                                               "(unpruned: " + unpruned_sizes + ")",
                                           mode));
    for (const std::string& format : formats) {
        if (format == "ply") continue;  // psnr_vs_mb.svg
        spec.title = "PSNR against size as " + format_label(format);
        spec.x_label = "size as " + format_label(format) + " (MB; log scale)";
        spec.series = per_method(rows, [&](const SweepRow& r) { return file_megabytes(r.measure, format); }, psnr);
        charts.sweep.push_back(write_chart(out_dir, "psnr_vs_mb_" + format + ".svg", spec,
                                           "PSNR against megabytes as " + format_label(format) + " (unpruned: " +
                                               decimals(file_megabytes(result.unpruned, format), 2) + " MB)",
                                           mode));
    }

    std::vector<std::string> degrees;
    std::vector<std::vector<double>> per_view(result.test_view_names.size());
    for (const ShDegreeMeasure& degree : result.sh_degrees) {
        degrees.push_back("SH " + std::to_string(degree.degree));
        for (size_t v = 0; v < per_view.size(); ++v) per_view[v].push_back(degree.view_psnr[v]);
    }
    const report::ChartSpec sh = report::paired_chart("PSNR of each test view by SH degree", "PSNR (dB)", degrees,
                                                  per_view, result.test_view_names);
    charts.sh = write_chart(out_dir, "psnr_by_sh_degree.svg", sh,
                            "PSNR against the photos of each test view (one line each) at each SH degree", mode);
    return charts;
}

}  // namespace vksplat::sweep::detail
