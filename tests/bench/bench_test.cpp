// The benchmark job beyond timing one view: measured device rates, the frame floor's arithmetic,
// scenes of a given size, scaling runs, and the JSON and charts they are reported in.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "support/gpu_fixture.hpp"
#include "support/scenes.hpp"
#include "vksplat/error.hpp"
#include "vksplat/bench/bench_report.hpp"

namespace vksplat::test {
namespace {

namespace fs = std::filesystem;

class Bench : public GpuTest {};

TEST_F(Bench, MeasuresPositiveDeviceRates) {
    const bench::DeviceRates rates =
        bench::measure_device_rates(context(), {.copy_bytes = 1 << 20, .sort_pairs = 1 << 14, .repetitions = 2});
    EXPECT_GT(rates.copy_bytes_per_ms, 0.0);
    EXPECT_GT(rates.sort_pairs_per_ms, 0.0);
    EXPECT_EQ(rates.copy_bytes, 1u << 20);
    EXPECT_EQ(rates.sort_pairs, 1u << 14);
}

TEST(BenchFloor, AddsMemoryAndSortTime) {
    bench::DeviceRates rates;
    rates.copy_bytes_per_ms = 1e9;   // 1 TB/s
    rates.sort_pairs_per_ms = 1e6;   // 1 G pairs/s at 32 bits (4 passes)
    bench::FrameWork work;
    work.scene_bytes = 100'000'000;
    work.tile_entries = 1'000'000;
    work.visible = 500'000;
    work.tile_key_bits = 12;         // 2 passes: half the cost per pair of a 32-bit sort
    work.pixels = 1'000'000;
    const bench::FrameFloor floor = bench::frame_floor(work, rates);
    EXPECT_EQ(floor.bytes, 100'000'000u + 48'000'000u + 16'000'000u);
    EXPECT_DOUBLE_EQ(floor.memory_ms, 0.164);
    EXPECT_DOUBLE_EQ(floor.sort_ms, 0.5 + 0.5);
    EXPECT_DOUBLE_EQ(floor.total_ms(), 1.164);
}

TEST(BenchSceneSize, ThinsBelowAndTilesAbove) {
    const GaussianCloud base = random_scene(5, 1000, 1);
    std::string label;
    EXPECT_EQ(bench::scene_of_size(base, 250, 1.0, &label).size(), 250u);
    EXPECT_EQ(label, "1/4 subset");
    EXPECT_EQ(bench::scene_of_size(base, 1000, 1.0, &label).size(), 1000u);
    EXPECT_EQ(bench::scene_of_size(base, 9000, 1.0, &label).size(), 9000u);
    EXPECT_EQ(label, "3x3 tiles");
    EXPECT_THROW(bench::scene_of_size(base, 0, 1.0), InputError);
}

TEST_F(Bench, ScalingRunsReportEveryPointAsJsonAndCharts) {
    Renderer renderer(context());
    renderer.set_scene(random_scene(6, 400, 0));
    bench::BenchmarkOptions options;
    options.warmup = 0;
    options.repetitions = 1;
    const Camera camera = forward_camera(64, 48, 50.0);
    bench::BenchReport report;
    report.device = context().info().name;
    report.views = bench::benchmark_views(renderer, {camera}, {0}, options, report.device);
    report.by_resolution = bench::benchmark_resolutions(renderer, camera, {{32, 32}, {96, 64}}, options);
    report.by_scene_size =
        bench::benchmark_scene_sizes(renderer, random_scene(7, 400, 0), {100, 1600}, 6.0, camera, options);
    ASSERT_EQ(report.by_resolution.size(), 2u);
    EXPECT_EQ(report.by_resolution[1].bench.width, 96);
    EXPECT_EQ(report.by_resolution[1].x, 96.0 * 64.0);
    ASSERT_EQ(report.by_scene_size.size(), 2u);
    EXPECT_EQ(report.by_scene_size[0].gaussians, 100u);
    EXPECT_EQ(report.by_scene_size[1].gaussians, 1600u);
    report.rates = bench::DeviceRates{.copy_bytes_per_ms = 1e6, .sort_pairs_per_ms = 1e3};
    report.pipelines = {{"blend", {{"Register Count", "82"}, {"Shared Memory Size", "22584"}}}};

    const nlohmann::json j = nlohmann::json::parse(bench::bench_json(report));
    EXPECT_EQ(j["pipelines"][0]["pipeline"], "blend");
    EXPECT_EQ(j["pipelines"][0]["statistics"]["Register Count"], "82");
    EXPECT_EQ(j["views"].size(), 1u);
    EXPECT_GT(j["views"][0]["visible"].get<int>(), 0);
    EXPECT_GT(j["views"][0]["floor"]["total_ms"].get<double>(), 0.0);
    EXPECT_EQ(j["by_resolution"][1]["label"], "96x64");
    EXPECT_EQ(j["by_scene_size"][1]["gaussians"], 1600);

    const fs::path dir = fs::temp_directory_path() / ("vksplat_bench_charts_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    const auto charts = bench::write_scaling_charts(dir, report, io::WriteMode::refuse_existing);
    ASSERT_EQ(charts.size(), 2u);
    for (const auto& chart : charts) {
        std::ifstream in(chart);
        std::stringstream text;
        text << in.rdbuf();
        EXPECT_NE(text.str().find("floor: memory + sort"), std::string::npos) << chart;
        EXPECT_NE(text.str().find("class=\"marker\""), std::string::npos) << chart;
    }
    EXPECT_THROW(bench::write_scaling_charts(dir, report, io::WriteMode::refuse_existing), InputError);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace vksplat::test
