#pragma once
// Timing of the renderer: each view is rendered repeatedly after a warm-up and the GPU's own
// timestamps give the median and minimum per frame and per stage. What `vksplat bench` does.
#include <chrono>
#include <cstddef>
#include <string>
#include <vector>

#include "vksplat/camera/camera.hpp"
#include "vksplat/render/renderer.hpp"

namespace vksplat::bench {

struct BenchmarkOptions {
    int warmup = 5;  // untimed frames first, and for at least kWarmupTime (see warm_up)
    int repetitions = 50;
    RenderSettings settings;
};

struct StageSummary {
    std::string stage;
    double median_ms = 0, min_ms = 0;
};

struct ViewBenchmark {
    size_t view = 0;
    int width = 0, height = 0;
    double median_ms = 0, min_ms = 0, max_ms = 0;  // whole frame, GPU time first to last dispatch
    std::vector<StageSummary> stages;
    uint32_t visible = 0, tile_entries = 0, tile_key_bits = 0;
    uint64_t device_bytes = 0, scene_bytes = 0;
    uint32_t chunks = 1;                // depth-ordered chunks per frame (memory budget)
};

struct BenchmarkResult {
    std::vector<ViewBenchmark> views;
    double mean_of_medians_ms = 0;      // the per-view medians averaged over the views
    std::string device;
};

BenchmarkResult benchmark_views(Renderer& renderer, const std::vector<Camera>& cameras,
                                const std::vector<size_t>& views, const BenchmarkOptions& options,
                                const std::string& device_name);

double median(std::vector<double> values);

// An idle GPU runs at a low clock for a while: on an H200, frames timed right after the CPU built
// a large scene ran 2-3x slow in every stage, though five warm-up frames had gone before, and a
// quarter of a second of copies once still measured 40% of the bandwidth. So
// warm-up lasts `runs` calls and at least kWarmupTime of wall time.
inline constexpr std::chrono::milliseconds kWarmupTime{1000};
template <class Run>
void warm_up(int runs, Run run) {
    const auto until = std::chrono::steady_clock::now() + kWarmupTime;
    for (int i = 0; i < runs || std::chrono::steady_clock::now() < until; ++i) run();
}

// The camera at another resolution with the same focal length per unit of width (the benchmark
// convention: lego at 1920x1080 multiplies fx and fy by 1920 / 800), principal point centred.
Camera with_resolution(const Camera& camera, int width, int height);

}  // namespace vksplat::bench
