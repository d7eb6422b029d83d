// vksplat bench: GPU time per frame and per stage, from timestamp queries, with the device's
// measured floor beside it; optionally the scaling with resolution and scene size.
#include <cstdio>
#include <filesystem>

#include "commands.hpp"
#include "number_checks.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/cameras.hpp"
#include "vksplat/io/npy.hpp"
#include "vksplat/bench/bench_report.hpp"
#include "vksplat/jobs/view_selection.hpp"
#include "vksplat/scene/tiled_scene.hpp"

namespace vksplat::cli {
namespace {

struct BenchArgs {
    GpuOptions gpu;
    std::string scene, cameras, views, tiled, json, charts, save_npy;
    int width = 0, height = 0, reps = 50, warmup = 5, sh_degree = 3;
    std::vector<float> background{0, 0, 0};
    bool half_sh = false, stats = false, floor = false, scaling = false, force = false, pipeline_stats = false;
};

std::array<int, 2> parse_grid(const std::string& text) {
    int nx = 0, ny = 0;
    char x = 0;
    if (std::sscanf(text.c_str(), "%d%c%d", &nx, &x, &ny) != 3 || (x != 'x' && x != 'X') || nx < 1 || ny < 1 ||
        nx > 64 || ny > 64)
        throw InputError("--tiled " + text, "expected NxM with 1 <= N, M <= 64, e.g. 5x5");
    return {nx, ny};
}

void print_view(const bench::ViewBenchmark& v, const std::optional<bench::DeviceRates>& rates) {
    std::printf("view %zu %dx%d: median %.3f ms, min %.3f ms, visible %u, tile entries %u, device memory %.1f MiB%s\n",
                v.view, v.width, v.height, v.median_ms, v.min_ms, v.visible, v.tile_entries,
                double(v.device_bytes) / (1 << 20),
                v.chunks > 1 ? (", " + std::to_string(v.chunks) + " chunks").c_str() : "");
    for (const auto& s : v.stages) std::printf("    %-14s %8.3f ms (min %.3f)\n", s.stage.c_str(), s.median_ms, s.min_ms);
    if (rates) {
        const bench::FrameFloor f = bench::frame_floor(bench::frame_work(v), *rates);
        std::printf("    floor: %.1f MB -> %.3f ms, sorts %.3f ms, total %.3f ms (frame is %.1fx its floor)\n",
                    double(f.bytes) * 1e-6, f.memory_ms, f.sort_ms, f.total_ms(), v.median_ms / f.total_ms());
    }
}

int run_bench(const BenchArgs& args) {
    const GaussianCloud base = read_scene_file(args.scene);
    GaussianCloud cloud = base;
    std::vector<Camera> cameras;
    if (!args.tiled.empty()) {
        const auto [nx, ny] = parse_grid(args.tiled);
        cloud = tile_scene(base, nx, ny, kTiledBenchmarkSpacing);
        cameras.push_back(tiled_benchmark_camera());
    } else if (!args.cameras.empty()) {
        cameras = io::read_cameras(args.cameras);
    } else {
        throw InputError("bench", "needs --cameras FILE, or --tiled NxN for the tiled benchmark scene");
    }
    if ((args.width > 0) != (args.height > 0)) throw InputError("bench", "give --width and --height together");
    if (args.width > 0)
        for (auto& c : cameras) c = bench::with_resolution(c, args.width, args.height);
    const auto views = jobs::parse_view_list(args.views, cameras.size());

    gpu::ContextOptions context_options = args.gpu.context_options();
    context_options.pipeline_statistics = args.pipeline_stats;
    gpu::Context context(context_options);
    if (args.pipeline_stats && !context.info().pipeline_statistics)
        std::fprintf(stderr, "warning: %s does not describe its pipelines (no VK_KHR_pipeline_executable_properties)\n",
                     context.info().name.c_str());
    Renderer renderer(context);
    const SceneStorage storage{.half_sh = args.half_sh};
    renderer.set_scene(cloud, storage);
    bench::BenchmarkOptions options;
    options.repetitions = args.reps;
    options.warmup = args.warmup;
    options.settings.background = {args.background[0], args.background[1], args.background[2]};
    options.settings.max_sh_degree = args.sh_degree;
    options.settings.gather_stats = args.stats;

    bench::BenchReport report;
    report.device = context.info().name;
    report.driver = context.info().driver;
    report.scene = args.scene + (args.tiled.empty() ? "" : " tiled " + args.tiled);
    report.gaussians = renderer.scene_size();
    report.half_sh = args.half_sh;
    report.blend_stats = args.stats;
    std::printf("device: %s (%s)\nscene: %s, %zu Gaussians%s%s\n", report.device.c_str(), report.driver.c_str(),
                report.scene.c_str(), size_t(report.gaussians), args.half_sh ? ", half-precision SH" : "",
                args.stats ? ", with the pruning scores' blend statistics" : "");
    if (args.floor) {
        report.rates = bench::measure_device_rates(context);
        std::printf("measured: copy %.0f GB/s (read + write), radix sort %.2f G pairs/s (32-bit keys), "
                    "dependent dispatch %.2f us\n",
                    report.rates->copy_bytes_per_ms * 1e-6, report.rates->sort_pairs_per_ms * 1e-6,
                    report.rates->dependent_dispatch_ms * 1e3);
    }
    report.views = bench::benchmark_views(renderer, cameras, views, options, report.device);
    for (const auto& v : report.views.views) print_view(v, report.rates);
    std::printf("mean of per-view medians: %.3f ms over %zu views\n", report.views.mean_of_medians_ms,
                report.views.views.size());

    const io::WriteMode mode = args.force ? io::WriteMode::overwrite : io::WriteMode::refuse_existing;
    if (!args.save_npy.empty()) {
        // The rendered views as float32 H x W x 3, to check accuracy where only numpy is at hand.
        std::filesystem::create_directories(args.save_npy);
        for (size_t view : views) {
            const RenderOutput out = renderer.render(cameras[view], options.settings);
            char name[64];
            std::snprintf(name, sizeof(name), "view_%04zu.npy", view);
            io::write_npy(std::filesystem::path(args.save_npy) / name, out.rgb.data(),
                          {size_t(out.height), size_t(out.width), 3}, mode);
        }
    }
    if (args.scaling) {
        const Camera& first = cameras[views.front()];
        report.by_resolution = bench::benchmark_resolutions(
            renderer, first, {{256, 256}, {512, 512}, {800, 800}, {1280, 720}, {1920, 1080}, {2560, 1440}, {3840, 2160}},
            options);
        // Scene sizes on the tiled benchmark camera, from a thinned scene to 7 x 7 copies.
        const uint64_t n = base.size();
        report.by_scene_size = bench::benchmark_scene_sizes(
            renderer, base, {10'000, 30'000, 100'000, n, 4 * n, 9 * n, 16 * n, 25 * n, 49 * n},
            kTiledBenchmarkSpacing, tiled_benchmark_camera(), options, storage);
        for (const auto* list : {&report.by_resolution, &report.by_scene_size})
            for (const auto& p : *list)
                std::printf("scaling %-14s %10llu Gaussians %9.0f px: %.3f ms\n", p.label.c_str(),
                            static_cast<unsigned long long>(p.gaussians), double(p.bench.width) * p.bench.height,
                            p.bench.median_ms);
    }
    report.pipelines = context.pipeline_statistics();
    for (const auto& p : report.pipelines) {
        std::printf("pipeline %s:", p.pipeline.c_str());
        for (const auto& [name, value] : p.values) std::printf(" %s = %s;", name.c_str(), value.c_str());
        std::printf("\n");
    }
    if (!args.json.empty()) bench::write_bench_json(args.json, report, mode);
    if (!args.charts.empty())
        for (const auto& path : bench::write_scaling_charts(args.charts, report, mode))
            std::printf("wrote %s\n", path.string().c_str());
    return 0;
}

}  // namespace

void register_bench(CLI::App& app, Action& action) {
    auto args = std::make_shared<BenchArgs>();
    CLI::App* cmd = app.add_subcommand("bench", "GPU time per frame and per stage (median over repeated frames)");
    cmd->add_option("scene", args->scene, "scene file (any format vksplat reads)")->required()->check(CLI::ExistingFile);
    cmd->add_option("--cameras", args->cameras, "camera file (cameras.json, COLMAP, transforms.json)")
        ->check(CLI::ExistingPath);
    cmd->add_option("--views", args->views, "views to time, e.g. 0,3,5-7 (default: all)");
    cmd->add_option("--width", args->width, "render at this width (focal lengths scale with it)")
        ->check(count_in(1, 16384));
    cmd->add_option("--height", args->height, "render at this height")->check(count_in(1, 16384));
    cmd->add_option("--tiled", args->tiled, "NxN copies of the scene seen by the tiled benchmark camera (e.g. 5x5)");
    cmd->add_option("--reps", args->reps, "timed frames per view")->capture_default_str()->check(count_in(1, 1000000));
    cmd->add_option("--warmup", args->warmup, "untimed frames first (and at least a second of them)")
        ->capture_default_str()
        ->check(count_in(0, 1000000));
    cmd->add_option("--background", args->background, "R,G,B in [0, 1]")
        ->delimiter(',')
        ->expected(3)
        ->check(number_in(0.0, 1.0));
    cmd->add_option("--sh-degree", args->sh_degree, "highest SH degree evaluated")->check(count_in(0, 3));
    cmd->add_flag("--half-sh", args->half_sh, "keep SH in half precision on the device (half the SH memory)");
    cmd->add_flag("--stats", args->stats,
                  "gather the per-Gaussian blend statistics that pruning scores read (the cost of scoring a view)");
    cmd->add_flag("--pipeline-stats", args->pipeline_stats,
                  "print what the driver says of each compiled pipeline (registers, shared memory, ...) where it can");
    cmd->add_flag("--floor", args->floor, "measure copy bandwidth and sort throughput; print each frame's floor");
    cmd->add_flag("--scaling", args->scaling,
                  "also time the first view at 256^2 .. 3840x2160 and the scene thinned and tiled to 1e4 .. 1.2e7");
    cmd->add_option("--json", args->json, "write every number to this file");
    cmd->add_option("--charts", args->charts, "folder for the scaling charts (SVG)");
    cmd->add_option("--save-npy", args->save_npy, "folder for each view's RGB as float32 .npy");
    cmd->add_flag("--force", args->force, "overwrite existing output files");
    add_gpu_options(*cmd, args->gpu);
    cmd->callback([&action, args] { action = [args] { return run_bench(*args); }; });
}

}  // namespace vksplat::cli
