#pragma once
// A benchmark's results as JSON (for scripts and for RESULTS.md) and its scaling charts as SVG,
// each point beside the physical floor of its frame (see device_floor.hpp).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "vksplat/gpu/context.hpp"
#include "vksplat/io/write_mode.hpp"
#include "vksplat/bench/bench_scaling.hpp"
#include "vksplat/bench/benchmark.hpp"
#include "vksplat/bench/device_floor.hpp"

namespace vksplat::bench {

struct BenchReport {
    std::string device, driver, scene;
    uint64_t gaussians = 0;
    bool half_sh = false;
    bool blend_stats = false;  // frames gathered the pruning statistics
    std::optional<DeviceRates> rates;           // with them, every view gets its floor
    BenchmarkResult views;
    std::vector<ScalingPoint> by_resolution, by_scene_size;
    std::vector<gpu::PipelineStatistics> pipelines;  // the driver's description of each pipeline, if asked for
};

// What a benchmarked frame could not avoid, from its counters.
FrameWork frame_work(const ViewBenchmark& view);

std::string bench_json(const BenchReport& report);
void write_bench_json(const std::filesystem::path& path, const BenchReport& report, io::WriteMode mode);

// Writes ms_vs_resolution.svg and ms_vs_gaussians.svg into `dir` (each only where the report has
// those points): median frame time, and with rates the floor (memory + sort) beside it. Returns
// the files written.
std::vector<std::filesystem::path> write_scaling_charts(const std::filesystem::path& dir, const BenchReport& report,
                                                        io::WriteMode mode);

}  // namespace vksplat::bench
