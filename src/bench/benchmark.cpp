#include "vksplat/bench/benchmark.hpp"

#include <algorithm>
#include <map>

#include "vksplat/error.hpp"

namespace vksplat::bench {

double median(std::vector<double> values) {
    if (values.empty()) return 0;
    std::sort(values.begin(), values.end());
    const size_t mid = values.size() / 2;
    return values.size() % 2 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

Camera with_resolution(const Camera& camera, int width, int height) {
    Camera out = camera;
    const double scale = double(width) / camera.width;
    out.width = width;
    out.height = height;
    out.fx = camera.fx * scale;
    out.fy = camera.fy * scale;
    out.cx = width / 2.0;
    out.cy = height / 2.0;
    return out;
}

BenchmarkResult benchmark_views(Renderer& renderer, const std::vector<Camera>& cameras,
                                const std::vector<size_t>& views, const BenchmarkOptions& options,
                                const std::string& device_name) {
    if (options.repetitions < 1) throw InputError("--reps", "must be at least 1");
    BenchmarkResult result;
    result.device = device_name;
    for (size_t view : views) {
        if (view >= cameras.size()) throw InputError("view " + std::to_string(view), "no such camera");
        const Camera& camera = cameras[view];
        // Warm-up: pipelines, buffer growth and clocks settle before anything is timed.
        warm_up(options.warmup, [&] { renderer.render_gpu_only(camera, options.settings); });

        std::vector<double> frames;
        std::vector<std::string> order;
        std::map<std::string, std::vector<double>> stages;
        for (int i = 0; i < options.repetitions; ++i) {
            renderer.render_gpu_only(camera, options.settings);
            const FrameStats& stats = renderer.last_frame();
            frames.push_back(stats.gpu_milliseconds);
            for (const auto& s : stats.stages) {
                if (!stages.count(s.stage)) order.push_back(s.stage);
                stages[s.stage].push_back(s.milliseconds);
            }
        }
        ViewBenchmark bench;
        bench.view = view;
        bench.width = camera.width;
        bench.height = camera.height;
        bench.median_ms = median(frames);
        bench.min_ms = *std::min_element(frames.begin(), frames.end());
        bench.max_ms = *std::max_element(frames.begin(), frames.end());
        for (const auto& name : order)
            bench.stages.push_back({name, median(stages[name]),
                                    *std::min_element(stages[name].begin(), stages[name].end())});
        const FrameStats& last = renderer.last_frame();
        bench.visible = last.visible;
        bench.tile_entries = last.tile_entries;
        bench.tile_key_bits = last.tile_key_bits;
        bench.device_bytes = last.device_bytes;
        bench.chunks = last.chunks;
        bench.scene_bytes = last.scene_bytes;
        result.views.push_back(bench);
        result.mean_of_medians_ms += bench.median_ms;
    }
    if (!result.views.empty()) result.mean_of_medians_ms /= double(result.views.size());
    return result;
}

}  // namespace vksplat::bench
