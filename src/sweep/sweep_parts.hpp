#pragma once
// The pieces of the sweep job (sweep.cpp), one file each: measuring a model, the CSV files, the
// charts, the comparison sheets and the report.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "vksplat/prune/selection.hpp"
#include "vksplat/report/html_report.hpp"
#include "vksplat/sweep/sweep.hpp"
#include "work_clock.hpp"

namespace vksplat::sweep::detail {

// The test views with the two pictures every render is compared with.
struct Targets {
    std::vector<Camera> cameras;
    std::vector<std::vector<float>> photos;    // RGB per camera
    std::vector<std::vector<float>> unpruned;  // the unpruned scene's renders
};

// Where the sweep's stages report: the caller's progress, with the time the whole sweep has left.
struct Reporter {
    const SweepProgress& progress;
    WorkClock clock;
    void step(const std::string& stage, size_t done, size_t total) const {
        if (progress.step) progress.step(stage, done, total, clock.seconds_left());
    }
};

// How many Gaussians a fraction keeps: as prune::select_ratio counts (round(f * N) dropped of all
// N, the lossless pass's drop included).
inline size_t kept_count(size_t n, double fraction) { return n - size_t(std::llround(fraction * double(n))); }

// Uploads `cloud`, renders each test view once and compares it with both targets, then times it
// as options.timing_* say (sweep_measure.cpp).
ModelMeasure measure_model(Renderer& renderer, const GaussianCloud& cloud, const Targets& targets,
                           const SweepOptions& options);

// sweep.csv: one row per (method, fraction); sh_degrees.csv: one row per (test view, SH degree)
// and a mean row per degree (sweep_csv.cpp).
void write_sweep_csv(const std::filesystem::path& path, const SweepResult& result, io::WriteMode mode);
void write_sh_csv(const std::filesystem::path& path, const SweepResult& result, io::WriteMode mode);

// The charts under out_dir/charts, as the report shows them (sweep_charts.cpp).
struct SweepCharts {
    std::vector<report::ReportImage> sweep;  // against the dropped fraction, the time and the size
    report::ReportImage sh;                  // per-view PSNR across SH degrees
};
SweepCharts write_sweep_charts(const std::filesystem::path& out_dir, const SweepResult& result, io::WriteMode mode);

// A PSNR as the report and the sheets print it: "31.20", or "identical" for +infinity (an identical
// pair; sweep.csv keeps "inf" for programs) (sweep_report.cpp).
std::string psnr_text(double psnr);

// One comparison sheet per test view (JPEG, under out_dir/sheets) of `ranking` cut at each of
// `fractions`, named after `name` (sweep_sheets.cpp).
std::vector<std::filesystem::path> write_sheets(Renderer& renderer, const GaussianCloud& cloud,
                                                const prune::Ranking& ranking, const std::string& name,
                                                const std::vector<double>& fractions, const Targets& targets,
                                                const SweepOptions& options, const std::vector<std::string>& stems,
                                                Reporter& reporter);

// report.html in out_dir (sweep_report.cpp).
void write_sweep_report(const std::filesystem::path& path, const SweepResult& result, const SweepOptions& options,
                        const SweepCharts& charts, io::WriteMode mode);

}  // namespace vksplat::sweep::detail
