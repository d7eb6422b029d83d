// chunked_bench: time per frame and device memory of one view rendered whole and under memory
// budgets that split it into about 2, 4 and 8 depth-ordered chunks (SceneStorage::memory_budget).
// Wall time includes what chunking adds on the host (depth partition, staging, one submission
// per chunk); GPU time is the sum of the chunks' dispatches.
// Usage: chunked_bench --scene lego/point_cloud.ply --cameras lego/cameras.json [--view 0]
//        [--chunks 2,4,8] [--reps 3] [--background 1,1,1] [--device NAME]
#include <CLI/CLI.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "render/frame_resources.hpp"
#include "render/gpu_scene.hpp"
#include "vksplat/io/cameras.hpp"
#include "vksplat/io/ply.hpp"
#include "vksplat/bench/benchmark.hpp"

namespace {

using namespace vksplat;

struct Result {
    double wall_ms = 0, gpu_ms = 0;
    FrameStats last;
};

Result measure(const gpu::Context& context, const GaussianCloud& cloud, const Camera& camera,
               const RenderSettings& settings, uint64_t budget, int reps) {
    Renderer renderer(context);
    renderer.set_scene(cloud, SceneStorage{.memory_budget = budget});
    renderer.render_gpu_only(camera, settings);  // warm-up: sizes the buffers, learns the entries
    std::vector<double> wall, gpu;
    for (int r = 0; r < reps; ++r) {
        const auto start = std::chrono::steady_clock::now();
        renderer.render_gpu_only(camera, settings);
        wall.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        gpu.push_back(renderer.last_frame().gpu_milliseconds);
    }
    return {bench::median(wall), bench::median(gpu), renderer.last_frame()};
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"time per frame and device memory, whole and in depth-ordered chunks"};
    std::string scene, cameras_path, device;
    size_t view = 0;
    int reps = 3;
    std::vector<uint32_t> chunk_targets{2, 4, 8};
    std::vector<float> background{1, 1, 1};
    app.add_option("--scene", scene, "scene (.ply)")->required();
    app.add_option("--cameras", cameras_path, "cameras")->required();
    app.add_option("--view", view, "camera index");
    app.add_option("--chunks", chunk_targets, "chunk counts to aim the budgets at")->delimiter(',');
    app.add_option("--reps", reps, "timed frames per budget (median)");
    app.add_option("--background", background, "R,G,B")->delimiter(',')->expected(3);
    app.add_option("--device", device, "GPU: index or part of its name");
    CLI11_PARSE(app, argc, argv);
    try {
        const GaussianCloud cloud = io::read_ply(scene);
        const Camera camera = io::read_cameras(cameras_path).at(view);
        gpu::Context context(gpu::ContextOptions{.device = device});
        RenderSettings settings;
        settings.background = {background[0], background[1], background[2]};

        const Result whole = measure(context, cloud, camera, settings, 0, reps);
        std::printf("device: %s\nscene: %s, %zu Gaussians, view %zu %dx%d\n", context.info().name.c_str(),
                    scene.c_str(), cloud.size(), view, camera.width, camera.height);
        std::printf("| budget | chunks | peak device memory | wall ms/frame | GPU ms/frame |\n|---|---|---|---|---|\n");
        std::printf("| none | %u | %.1f MiB | %.3f | %.3f |\n", whole.last.chunks, whole.last.device_bytes / 1048576.0,
                    whole.wall_ms, whole.gpu_ms);
        // Budgets sized like the renderer's planner: a chunk of n / K Gaussians with the tile
        // entries per Gaussian the whole frame needed, plus the renderer's 25% headroom.
        const double entries_per_gaussian = 1.25 * whole.last.tile_entries / std::max(whole.last.visible, 1u);
        const uint32_t pixels = uint32_t(camera.width * camera.height);
        const uint32_t tiles = uint32_t(((camera.width + 15) / 16) * ((camera.height + 15) / 16));
        for (const uint32_t target : chunk_targets) {
            const uint32_t chunk = uint32_t((cloud.size() + target - 1) / target);
            uint64_t budget = render::GpuScene::bytes_for(chunk, cloud.sh_degree, false) +
                                    render::FrameResources::bytes_for(
                                        context, chunk, uint32_t(std::ceil(chunk * entries_per_gaussian)), pixels, tiles,
                                        true);
            // The renderer learns the tile entries per Gaussian from its densest chunk, more than
            // the frame's mean: raise the budget until the planner gets down to the target.
            Result r = measure(context, cloud, camera, settings, budget, reps);
            for (int tries = 0; r.last.chunks > target && tries < 20; ++tries) {
                budget = uint64_t(double(budget) * 1.02);
                r = measure(context, cloud, camera, settings, budget, reps);
            }
            std::printf("| %.1f MiB | %u | %.1f MiB | %.3f | %.3f |\n", budget / 1048576.0, r.last.chunks,
                        r.last.device_bytes / 1048576.0, r.wall_ms, r.gpu_ms);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
