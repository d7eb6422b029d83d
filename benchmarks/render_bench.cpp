// render_bench: times the renderer on real scenes (median GPU time per frame and per stage) and
// optionally saves the rendered views as float32 .npy for an accuracy check on the GPU host.
// Usage: render_bench SCENE.ply --cameras cameras.json [--views 0-12] [--size 1920x1080]
//                    [--tiled 5] [--reps 50] [--background 1,1,1] [--save DIR]
#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>

#include "vksplat/io/cameras.hpp"
#include "vksplat/io/npy.hpp"
#include "vksplat/io/ply.hpp"
#include "vksplat/jobs/benchmark.hpp"
#include "vksplat/jobs/view_selection.hpp"
#include "vksplat/tiled_scene.hpp"

int main(int argc, char** argv) {
    using namespace vksplat;
    CLI::App app{"render_bench: GPU time per frame and per stage"};
    std::string scene_path, cameras_path, views_text, size_text, save_dir, device;
    int tiled = 0, reps = 50, warmup = 5;
    std::vector<float> background{0, 0, 0};
    app.add_option("scene", scene_path)->required();
    app.add_option("--cameras", cameras_path);
    app.add_option("--views", views_text);
    app.add_option("--size", size_text, "WxH; focal lengths scale with the width");
    app.add_option("--tiled", tiled, "N: N x N copies 2.6 apart, seen by the benchmark camera");
    app.add_option("--reps", reps);
    app.add_option("--warmup", warmup);
    app.add_option("--background", background)->delimiter(',')->expected(3);
    app.add_option("--save", save_dir, "write each view's rgb as float32 .npy here");
    app.add_option("--device", device);
    CLI11_PARSE(app, argc, argv);
    try {
        GaussianCloud cloud = io::read_ply(scene_path);
        std::vector<Camera> cameras;
        if (tiled > 0) {
            cloud = tile_scene(cloud, tiled, tiled, 2.6);
            cameras.push_back(tiled_benchmark_camera());
        } else {
            cameras = io::read_inria_cameras(cameras_path);
        }
        if (!size_text.empty()) {
            int w = 0, h = 0;
            if (std::sscanf(size_text.c_str(), "%dx%d", &w, &h) != 2) throw InputError("--size", "expected WxH");
            for (auto& c : cameras) c = jobs::with_resolution(c, w, h);
        }
        const auto views = jobs::parse_view_list(views_text, cameras.size());

        gpu::Context context({device, false});
        Renderer renderer(context);
        renderer.set_scene(cloud);
        jobs::BenchmarkOptions options;
        options.repetitions = reps;
        options.warmup = warmup;
        options.settings.background = {background[0], background[1], background[2]};
        const auto result = jobs::benchmark_views(renderer, cameras, views, options, context.info().name);

        std::printf("device: %s (%s)\nscene: %s, %zu Gaussians\n", context.info().name.c_str(),
                    context.info().driver.c_str(), scene_path.c_str(), cloud.size());
        for (const auto& v : result.views) {
            std::printf("view %zu %dx%d: median %.3f ms, min %.3f ms, visible %u, tile entries %u, device %.1f MiB\n",
                        v.view, v.width, v.height, v.median_ms, v.min_ms, v.visible, v.tile_entries,
                        double(v.device_bytes) / (1 << 20));
            for (const auto& s : v.stages) std::printf("    %-14s %8.3f ms (min %.3f)\n", s.stage.c_str(), s.median_ms, s.min_ms);
        }
        std::printf("mean of per-view medians: %.3f ms over %zu views\n", result.mean_of_medians_ms, result.views.size());

        if (!save_dir.empty()) {
            std::filesystem::create_directories(save_dir);
            for (size_t view : views) {
                const RenderOutput out = renderer.render(cameras[view], options.settings);
                char name[64];
                std::snprintf(name, sizeof(name), "view_%04zu.npy", view);
                io::write_npy(std::filesystem::path(save_dir) / name, out.rgb.data(),
                              {size_t(out.height), size_t(out.width), 3}, io::WriteMode::overwrite);
            }
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "render_bench: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
