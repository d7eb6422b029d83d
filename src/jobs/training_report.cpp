#include "jobs/training_report.hpp"

#include <cmath>
#include <cstdio>

#include "vksplat/report/chart.hpp"
#include "vksplat/report/html_report.hpp"

namespace vksplat::jobs {
namespace {

namespace fs = std::filesystem;

constexpr const char* kCountChart = "training_gaussians.svg";
constexpr const char* kPsnrChart = "training_test_psnr.svg";
constexpr const char* kPsnrCountChart = "training_psnr_by_count.svg";

std::string number(double value, const char* format) {
    char text[64];
    std::snprintf(text, sizeof text, format, value);
    return text;
}

report::ChartSpec line_chart(std::string title, std::string x_label, std::string y_label, report::Series series) {
    report::ChartSpec chart;
    chart.title = std::move(title);
    chart.x_label = std::move(x_label);
    chart.y_label = std::move(y_label);
    chart.series = {std::move(series)};
    return chart;
}

}  // namespace

std::vector<fs::path> training_report_files(const fs::path& folder) {
    return {folder / "report.html", folder / kCountChart, folder / kPsnrChart, folder / kPsnrCountChart};
}

void write_training_report(const fs::path& folder, const TrainResult& result, const std::string& data,
                           io::WriteMode mode) {
    report::Series count{"Gaussians", {}, {}}, psnr_by_iteration{"test PSNR", {}, {}}, psnr_by_count{"test PSNR", {}, {}};
    for (const auto& s : result.history) {
        count.x.push_back(double(s.iteration));
        count.y.push_back(double(s.gaussians));
        if (s.test_psnr && std::isfinite(*s.test_psnr)) {
            psnr_by_iteration.x.push_back(double(s.iteration));
            psnr_by_iteration.y.push_back(*s.test_psnr);
            psnr_by_count.x.push_back(double(s.gaussians));
            psnr_by_count.y.push_back(*s.test_psnr);
        }
    }
    report::write_svg_chart(folder / kCountChart, line_chart("Gaussians over the run", "iteration", "Gaussians", count),
                            mode);
    report::write_svg_chart(folder / kPsnrChart,
                            line_chart("Test PSNR over the run", "iteration", "test PSNR (dB)", psnr_by_iteration), mode);
    report::write_svg_chart(folder / kPsnrCountChart,
                            line_chart("Test PSNR against the count", "Gaussians", "test PSNR (dB)", psnr_by_count), mode);

    report::HtmlReport page("Training of " + data);
    const bool measured = !result.test.psnr.empty();
    page.add_paragraph(std::to_string(result.iterations) + " iterations, " + result.strategy + " recipe: " +
                       std::to_string(result.gaussians) + " Gaussians" +
                       (measured ? ", test PSNR " + number(result.test.mean_psnr, "%.3f") + " dB on " +
                                       std::to_string(result.test.psnr.size()) + " held-out views"
                                 : ", no held-out views"));
    page.add_images_row({{kCountChart, "Gaussians after every 500 iterations"},
                         {kPsnrChart, psnr_by_iteration.x.empty()
                                          ? "test PSNR: measured at the end only (--evaluate-every N measures it "
                                            "during the run)"
                                          : "test PSNR where measured (--evaluate-every)"},
                         {kPsnrCountChart, "test PSNR against the Gaussians held when it was measured"}});
    std::vector<std::vector<std::string>> rows;
    for (const auto& s : result.history)
        if (s.test_psnr) rows.push_back({std::to_string(s.iteration), std::to_string(s.gaussians), number(*s.test_psnr, "%.3f")});
    if (!rows.empty()) page.add_table({"iteration", "Gaussians", "test PSNR (dB)"}, rows);
    page.add_table({"", ""}, {{"seconds (steps and densification)", number(result.seconds, "%.1f")},
                              {"of which densification and pruning", number(result.strategy_seconds, "%.1f")},
                              {"GPU ms per iteration (median)", number(result.gpu_ms_per_iteration, "%.3f")},
                              {"peak device memory (MB)", number(double(result.peak_device_bytes) / 1e6, "%.1f")},
                              {"removed by blend weight", std::to_string(result.importance_prunes.pruned)},
                              {"test SSIM", measured ? number(result.test.mean_ssim, "%.4f") : "-"}});
    page.write(folder / "report.html", mode);
}

}  // namespace vksplat::jobs
