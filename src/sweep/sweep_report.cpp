// report.html of a sweep: what was run, the charts, the table, the SH degrees and the sheets.
#include <cmath>
#include <cstdio>
#include <string>

#include "sweep_parts.hpp"
#include "vksplat/report/comparison_sheet.hpp"

namespace vksplat::sweep::detail {
namespace {

std::string format(const char* pattern, double value) {
    char text[64];
    std::snprintf(text, sizeof(text), pattern, value);
    return text;
}

std::string megabytes(size_t bytes) { return format("%.2f", double(bytes) / 1e6); }

std::string timing_rule(const SweepResult& result, const SweepOptions& options) {
    if (options.timing_repetitions == 0)
        return "the median over the test views of each one's measuring render; the spread is the fastest and the "
               "slowest of those renders";
    const size_t views = options.timing_views == 0 ? result.test_views.size()
                                                   : std::min(options.timing_views, result.test_views.size());
    return "the median of " + std::to_string(options.timing_repetitions) + " frames per view after " +
           std::to_string(options.timing_warmup) + " untimed, averaged over the first " + std::to_string(views) +
           " test views; the spread is each view's fastest and slowest frame, averaged the same way";
}

void add_summary(report::HtmlReport& report, const SweepResult& result, const SweepOptions& options) {
    const ModelMeasure& u = result.unpruned;
    report.add_paragraph("Scene " + options.scene_label + ": " + std::to_string(u.gaussians) + " Gaussians (" +
                         megabytes(u.bytes) + " MB as INRIA PLY) after sanitising" +
                         (result.sanitize.changed() ? " (" + result.sanitize.summary() + ")" : std::string()) +
                         ". Measured on " + std::to_string(result.test_views.size()) +
                         " test views against their photos: PSNR " + format("%.3f", u.psnr) + " dB, SSIM " +
                         format("%.4f", u.ssim) + ", " + format("%.2f", u.ms_per_frame) +
                         " ms per frame (GPU timestamps, " + timing_rule(result, options) + ").");
    std::string scoring = "Scores come from one pass over " + std::to_string(result.train_views.size()) +
                          " training views with per-Gaussian statistics (" + format("%.1f", result.scoring_seconds) +
                          " s)";
    if (result.plain_render_seconds > 0)
        scoring += "; rendering the same views without statistics took " +
                   format("%.1f", result.plain_render_seconds) + " s, so scoring cost " +
                   format("%.2f", result.scoring_seconds / result.plain_render_seconds) + "x plain rendering";
    report.add_paragraph(scoring + ". Each method is scored once from them; every fraction cuts that ranking. The "
                                   "lossless pass (Gaussians that reach alpha 1/255 on no pixel of those views) "
                                   "applies first to every method and dropped " +
                         std::to_string(result.lossless_dropped) +
                         ", so fraction 0 is that pass alone. Fractions count all Gaussians, the lossless pass's "
                         "included.");
    if (options.cluster)
        report.add_paragraph(
            "The cluster method is cluster pruning (vksplat cluster) at its settings: region maps of up to " +
            std::to_string(options.cluster_options.max_views) +
            " training views, clusters of neighbouring Gaussians whose regions agree, each Gaussian ranked by its "
            "cluster's G*, so that a kept count takes clusters whole from the best down (the last one partly), "
            "after the same lossless pass. Its stages took " +
            format("%.1f", result.cluster_seconds) + " s.");
}

std::string spread(const ModelMeasure& m) { return format("%.2f", m.ms_min) + " – " + format("%.2f", m.ms_max); }

void add_table(report::HtmlReport& report, const SweepResult& result) {
    std::vector<std::vector<std::string>> rows;
    const ModelMeasure& u = result.unpruned;
    rows.push_back({"unpruned", "-", "0", std::to_string(u.gaussians), megabytes(u.bytes), format("%.3f", u.psnr),
                    "0", format("%.4f", u.ssim), psnr_text(u.psnr_vs_unpruned), "1",
                    format("%.2f", u.ms_per_frame), spread(u), "-"});
    for (const SweepRow& row : result.rows) {
        const ModelMeasure& m = row.measure;
        rows.push_back({row.method, fraction_label(row.fraction),
                        format("%.4f", row.dropped), std::to_string(m.gaussians), megabytes(m.bytes),
                        format("%.3f", m.psnr), format("%+.3f", row.delta_psnr), format("%.4f", m.ssim),
                        psnr_text(m.psnr_vs_unpruned), format("%.4f", m.ssim_vs_unpruned),
                        format("%.2f", m.ms_per_frame), spread(m),
                        row.recover_iterations ? format("%.1f", row.recover_seconds) : std::string("-")});
    }
    report.add_table({"method", "fraction", "dropped", "Gaussians", "MB", "PSNR", "ΔPSNR", "SSIM",
                      "PSNR vs unpruned", "SSIM vs unpruned", "ms/frame", "ms fastest – slowest", "re-fit s"},
                     std::move(rows));
}

void add_sh_degrees(report::HtmlReport& report, const SweepResult& result, const SweepCharts& charts) {
    report.add_heading("SH degrees (unpruned)");
    std::vector<std::vector<std::string>> rows;
    for (const ShDegreeMeasure& d : result.sh_degrees)
        rows.push_back({std::to_string(d.degree), megabytes(d.bytes), format("%.3f", d.psnr), format("%.4f", d.ssim),
                        d.degree == 0 ? "-" : format("%+.3f", d.psnr - result.sh_degrees[size_t(d.degree) - 1].psnr)});
    report.add_table({"SH degree", "MB", "PSNR", "SSIM", "gain over the degree below (dB)"}, std::move(rows));
    if (result.sh_degrees.size() > 1) {
        const ShDegreeMeasure& low = result.sh_degrees.front();
        const ShDegreeMeasure& high = result.sh_degrees.back();
        size_t better = 0;
        for (size_t v = 0; v < high.view_psnr.size(); ++v) better += high.view_psnr[v] > low.view_psnr[v];
        report.add_paragraph("Mean gain from SH degree 0 to " + std::to_string(high.degree) + ": " +
                             format("%+.3f", high.psnr - low.psnr) + " dB (paired over the test views; " +
                             std::to_string(better) + " of " + std::to_string(high.view_psnr.size()) +
                             " views gain).");
    }
    report.add_image(charts.sh.relative_path, charts.sh.caption);
}

void add_sheets(report::HtmlReport& report, const SweepResult& result, const SweepOptions& options) {
    report.add_heading("Comparison sheets");
    const std::string& best = result.best_method;
    if (result.sheets.empty()) {
        report.add_paragraph("No sheets: none of the sheet fractions was swept.");
        return;
    }
    report.add_paragraph("For the best method, " + best +
                         " (highest PSNR against the photos averaged over the fractions above 0), at each of the "
                         "fractions below, every test view: photo | unpruned | pruned, each render with its PSNR "
                         "against the photo | error of the pruned render against the unpruned one (mean absolute "
                         "error over the channels, colour bar from 0 to " +
                         format("%g", options.sheet_max_error) +
                         "), with its PSNR | the square where that error is largest (outlined in cyan on the "
                         "renders), enlarged: unpruned above, pruned below. Sheets are JPEG (quality " +
                         std::to_string(report::kJpegQuality) + ").");
    const size_t views = result.test_view_names.size();
    for (size_t f = 0; f < result.sheet_fractions.size(); ++f) {
        report.add_heading(best + ", " + fraction_label(result.sheet_fractions[f]) + " dropped");
        for (size_t v = 0; v < views; ++v)
            report.add_image(result.sheets[f * views + v].generic_string(), result.test_view_names[v]);
    }
}

}  // namespace

std::string psnr_text(double psnr) { return std::isinf(psnr) ? "identical" : format("%.2f", psnr); }

void write_sweep_report(const std::filesystem::path& path, const SweepResult& result, const SweepOptions& options,
                        const SweepCharts& charts, io::WriteMode mode) {
    report::HtmlReport report("Pruning sweep" + (options.scene_label.empty() ? "" : ": " + options.scene_label));
    report.add_note(summary_line(result), report::HtmlReport::Note::summary);
    if (result.device_is_cpu)
        report.add_note("Timed on " + result.device +
                            ", a CPU device: its frame times say little about any GPU's (a pruned model may even "
                            "time slower than the unpruned one). Time on a GPU to compare speeds.",
                        report::HtmlReport::Note::warning);
    add_summary(report, result, options);
    report.add_paragraph("Tables: sweep.csv (one row per method and fraction) and sh_degrees.csv. The view totals "
                         "are in totals.npy: vksplat prune --load-scores totals.npy cuts any method at any count "
                         "from them without rendering the training views again.");
    report.add_images_row(charts.sweep);
    report.add_heading("Every method at every fraction");
    add_table(report, result);
    add_sh_degrees(report, result, charts);
    add_sheets(report, result, options);
    report.write(path, mode);
}

}  // namespace vksplat::sweep::detail
