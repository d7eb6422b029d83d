// The sweep's comparison sheets: the best method's pruned renders beside the photo, the unpruned
// render, their error and its largest-error window, each under its PSNR.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "sweep_parts.hpp"
#include "vksplat/eval/metrics.hpp"
#include "vksplat/report/comparison_sheet.hpp"

namespace vksplat::sweep::detail {
namespace {

namespace fs = std::filesystem;

// "31.20 dB", or "identical" for an identical pair.
std::string decibels(double psnr) { return std::isinf(psnr) ? "identical" : psnr_text(psnr) + " dB"; }

// One sheet: photo | unpruned | pruned | error vs unpruned | the window where that error is
// largest, zoomed (unpruned above, pruned below; outlined on the pictures), each render under its
// PSNR against the photo, the error map under the pruned render's PSNR against the unpruned one.
std::vector<report::SheetPanel> sheet_panels(const std::vector<float>& photo, const std::vector<float>& unpruned,
                                             const std::vector<float>& pruned, int w, int h,
                                             const std::string& pruned_name, float max_error) {
    const report::ErrorWindow window =
        report::largest_error_window(pruned.data(), unpruned.data(), w, h, std::max(8, std::min(w, h) / 8));
    const std::array<float, 3> outline{0.0f, 0.9f, 1.0f};
    report::SheetPanel unpruned_panel{"unpruned, " + decibels(eval::psnr(unpruned.data(), photo.data(), w, h)), w, h,
                                      unpruned};
    report::SheetPanel pruned_panel{pruned_name + ", " + decibels(eval::psnr(pruned.data(), photo.data(), w, h)), w,
                                    h, pruned};
    report::SheetPanel zoom = report::zoomed_window_panel(unpruned.data(), pruned.data(), w, h, window,
                                                          "largest error, zoomed");
    report::outline_window(unpruned_panel, window, outline);
    report::outline_window(pruned_panel, window, outline);
    return {{"photo", w, h, photo},
            std::move(unpruned_panel),
            std::move(pruned_panel),
            report::heat_map_panel(pruned.data(), unpruned.data(), w, h, max_error,
                                   "error vs unpruned, " + decibels(eval::psnr(pruned.data(), unpruned.data(), w, h))),
            std::move(zoom)};
}

}  // namespace

// One sheet per test view (sheet_panels, as JPEG) for `method` at each fraction.
std::vector<fs::path> write_sheets(Renderer& renderer, const GaussianCloud& cloud, const prune::Ranking& ranking,
                                   const std::string& name, const std::vector<double>& fractions,
                                   const Targets& targets, const SweepOptions& options,
                                   const std::vector<std::string>& stems, Reporter& reporter) {
    std::vector<fs::path> sheets;
    const size_t total = fractions.size() * targets.cameras.size();
    for (double fraction : fractions) {
        const GaussianCloud pruned = cloud.subset(ranking.keep_best(kept_count(cloud.size(), fraction)));
        renderer.set_scene(pruned);
        const std::string label = fraction_label(fraction);
        for (size_t v = 0; v < targets.cameras.size(); ++v) {
            reporter.step("comparison sheets", sheets.size(), total);
            reporter.clock.begin(Work::sheet);
            const RenderOutput image = renderer.render(targets.cameras[v], options.settings);
            const int w = image.width, h = image.height;
            const fs::path relative = fs::path("sheets") / (stems[v] + "_" + name + "_" + label + ".jpg");
            report::write_comparison_sheet(options.out_dir / relative,
                                           sheet_panels(targets.photos[v], targets.unpruned[v], image.rgb, w, h,
                                                        name + ", " + label + " dropped", options.sheet_max_error),
                                           options.mode);
            sheets.push_back(relative);
            reporter.clock.advance(1);
        }
    }
    reporter.clock.end();
    reporter.step("comparison sheets", total, total);
    return sheets;
}

}  // namespace vksplat::sweep::detail
