// One model of the sweep measured: quality on the test views against the photos and against the
// unpruned render, GPU time per frame, size as PLY and as a file of each format asked for.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "sweep_parts.hpp"
#include "vksplat/eval/metrics.hpp"
#include "vksplat/bench/benchmark.hpp"
#include "vksplat/prune/size_budget.hpp"

namespace vksplat::sweep::detail {
namespace {

// The PSNR of the views' pooled error: views identical to the unpruned render give +infinity
// each, so a plain mean of per-view PSNRs would hide the others behind one identical view.
double pooled_psnr(const std::vector<double>& view_psnr) {
    if (view_psnr.empty()) return 0;
    double mse = 0;
    for (double p : view_psnr) mse += std::pow(10.0, -p / 10.0);
    mse /= double(view_psnr.size());
    return mse > 0 ? -10.0 * std::log10(mse) : std::numeric_limits<double>::infinity();
}

double mean(const std::vector<double>& values) {
    return values.empty() ? 0.0 : std::accumulate(values.begin(), values.end(), 0.0) / double(values.size());
}

// ms_per_frame and its spread (ModelMeasure).
struct FrameTime {
    double median = 0, min = 0, max = 0;
};

FrameTime time_per_frame(Renderer& renderer, const Targets& targets, const SweepOptions& options,
                         const std::vector<double>& measuring_ms) {
    if (options.timing_repetitions == 0) {
        if (measuring_ms.empty()) return {};
        const auto [min, max] = std::minmax_element(measuring_ms.begin(), measuring_ms.end());
        return {bench::median(measuring_ms), *min, *max};
    }
    const size_t count = options.timing_views == 0 ? targets.cameras.size()
                                                   : std::min(options.timing_views, targets.cameras.size());
    std::vector<size_t> views(count);
    std::iota(views.begin(), views.end(), size_t{0});
    bench::BenchmarkOptions timing;
    timing.warmup = options.timing_warmup;
    timing.repetitions = options.timing_repetitions;
    timing.settings = options.settings;
    const bench::BenchmarkResult result = bench::benchmark_views(renderer, targets.cameras, views, timing, "");
    FrameTime time{result.mean_of_medians_ms, 0, 0};
    for (const bench::ViewBenchmark& view : result.views) {
        time.min += view.min_ms / double(result.views.size());
        time.max += view.max_ms / double(result.views.size());
    }
    return time;
}

}  // namespace

ModelMeasure measure_model(Renderer& renderer, const GaussianCloud& cloud, const Targets& targets,
                           const SweepOptions& options) {
    ModelMeasure m;
    m.gaussians = cloud.size();
    m.bytes = cloud.ply_bytes();
    renderer.set_scene(cloud);
    std::vector<double> ssim, psnr_unpruned, ssim_unpruned, gpu_ms;
    for (size_t v = 0; v < targets.cameras.size(); ++v) {
        const RenderOutput image = renderer.render(targets.cameras[v], options.settings);
        gpu_ms.push_back(renderer.last_frame().gpu_milliseconds);
        const float* rgb = image.rgb.data();
        m.view_psnr.push_back(eval::psnr(rgb, targets.photos[v].data(), image.width, image.height));
        ssim.push_back(eval::ssim(rgb, targets.photos[v].data(), image.width, image.height));
        psnr_unpruned.push_back(eval::psnr(rgb, targets.unpruned[v].data(), image.width, image.height));
        ssim_unpruned.push_back(eval::ssim(rgb, targets.unpruned[v].data(), image.width, image.height));
    }
    m.psnr = mean(m.view_psnr);
    m.ssim = mean(ssim);
    m.psnr_vs_unpruned = pooled_psnr(psnr_unpruned);
    m.ssim_vs_unpruned = mean(ssim_unpruned);
    const FrameTime time = time_per_frame(renderer, targets, options, gpu_ms);
    m.ms_per_frame = time.median;
    m.ms_min = time.min;
    m.ms_max = time.max;
    for (const std::string& format : options.size_formats)
        m.file_bytes.emplace_back(format, prune::scene_file_bytes(cloud, format));
    return m;
}

}  // namespace vksplat::sweep::detail
