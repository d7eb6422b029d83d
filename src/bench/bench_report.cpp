#include "vksplat/bench/bench_report.hpp"

#include <nlohmann/json.hpp>

#include "vksplat/report/chart.hpp"

namespace vksplat::bench {

namespace {

nlohmann::json view_json(const ViewBenchmark& view, const std::optional<DeviceRates>& rates) {
    nlohmann::json j{{"view", view.view},
                     {"width", view.width},
                     {"height", view.height},
                     {"median_ms", view.median_ms},
                     {"min_ms", view.min_ms},
                     {"visible", view.visible},
                     {"tile_entries", view.tile_entries},
                     {"device_mib", double(view.device_bytes) / (1 << 20)},
                     {"scene_mib", double(view.scene_bytes) / (1 << 20)}};
    nlohmann::json stages = nlohmann::json::array();
    for (const auto& s : view.stages) stages.push_back({{"stage", s.stage}, {"median_ms", s.median_ms}, {"min_ms", s.min_ms}});
    j["stages"] = stages;
    if (rates) {
        const FrameFloor floor = frame_floor(frame_work(view), *rates);
        j["floor"] = {{"bytes", floor.bytes},
                      {"memory_ms", floor.memory_ms},
                      {"sort_ms", floor.sort_ms},
                      {"total_ms", floor.total_ms()}};
    }
    return j;
}

nlohmann::json points_json(const std::vector<ScalingPoint>& points, const std::optional<DeviceRates>& rates) {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& p : points) {
        nlohmann::json j = view_json(p.bench, rates);
        j["label"] = p.label;
        j["x"] = p.x;
        j["gaussians"] = p.gaussians;
        list.push_back(j);
    }
    return list;
}

void write_chart(const std::filesystem::path& path, std::string title, std::string x_label,
                 const std::vector<ScalingPoint>& points, const std::optional<DeviceRates>& rates, io::WriteMode mode) {
    report::Series frame{"median frame (GPU timestamps)", {}, {}}, floor{"floor: memory + sort", {}, {}},
        memory{"floor: bytes / copy bandwidth", {}, {}};
    for (const auto& p : points) {
        frame.x.push_back(p.x);
        frame.y.push_back(p.bench.median_ms);
        if (!rates) continue;
        const FrameFloor f = frame_floor(frame_work(p.bench), *rates);
        for (auto* s : {&floor, &memory}) s->x.push_back(p.x);
        floor.y.push_back(f.total_ms());
        memory.y.push_back(f.memory_ms);
    }
    report::ChartSpec spec;
    spec.title = std::move(title);
    spec.x_label = std::move(x_label);
    spec.y_label = "ms per frame";
    spec.log_x = true;
    spec.y_min = 0;
    spec.series.push_back(frame);
    if (rates) {
        spec.series.push_back(floor);
        spec.series.push_back(memory);
    }
    report::write_svg_chart(path, spec, mode);
}

}  // namespace

FrameWork frame_work(const ViewBenchmark& view) {
    FrameWork work;
    work.scene_bytes = view.scene_bytes;
    work.visible = view.visible;
    work.tile_entries = view.tile_entries;
    work.tile_key_bits = view.tile_key_bits;
    work.pixels = uint64_t(view.width) * uint64_t(view.height);
    return work;
}

std::string bench_json(const BenchReport& report) {
    nlohmann::json j{{"device", report.device},
                     {"driver", report.driver},
                     {"scene", report.scene},
                     {"gaussians", report.gaussians},
                     {"half_sh", report.half_sh},
                     {"blend_stats", report.blend_stats},
                     {"mean_of_medians_ms", report.views.mean_of_medians_ms}};
    if (report.rates)
        j["rates"] = {{"copy_gb_per_s", report.rates->copy_bytes_per_ms * 1e-6},
                      {"sort_g_pairs_per_s", report.rates->sort_pairs_per_ms * 1e-6},
                      {"copy_bytes", report.rates->copy_bytes},
                      {"sort_pairs", report.rates->sort_pairs},
                      {"dependent_dispatch_us", report.rates->dependent_dispatch_ms * 1e3}};
    nlohmann::json views = nlohmann::json::array();
    for (const auto& v : report.views.views) views.push_back(view_json(v, report.rates));
    j["views"] = views;
    if (!report.by_resolution.empty()) j["by_resolution"] = points_json(report.by_resolution, report.rates);
    if (!report.by_scene_size.empty()) j["by_scene_size"] = points_json(report.by_scene_size, report.rates);
    if (!report.pipelines.empty()) {
        nlohmann::json pipelines = nlohmann::json::array();
        for (const auto& p : report.pipelines) {
            nlohmann::json values = nlohmann::json::object();
            for (const auto& [name, value] : p.values) values[name] = value;
            pipelines.push_back({{"pipeline", p.pipeline}, {"statistics", values}});
        }
        j["pipelines"] = pipelines;
    }
    return j.dump(2) + "\n";
}

void write_bench_json(const std::filesystem::path& path, const BenchReport& report, io::WriteMode mode) {
    const std::string text = bench_json(report);
    io::write_file_atomically(path, mode, [&](std::ostream& out) { out << text; });
}

std::vector<std::filesystem::path> write_scaling_charts(const std::filesystem::path& dir, const BenchReport& report,
                                                        io::WriteMode mode) {
    std::vector<std::filesystem::path> written;
    std::filesystem::create_directories(dir);
    if (!report.by_resolution.empty()) {
        written.push_back(dir / "ms_vs_resolution.svg");
        write_chart(written.back(), "Frame time against resolution (" + report.device + ")", "pixels",
                    report.by_resolution, report.rates, mode);
    }
    if (!report.by_scene_size.empty()) {
        written.push_back(dir / "ms_vs_gaussians.svg");
        write_chart(written.back(), "Frame time against scene size (" + report.device + ")", "Gaussians",
                    report.by_scene_size, report.rates, mode);
    }
    return written;
}

}  // namespace vksplat::bench
