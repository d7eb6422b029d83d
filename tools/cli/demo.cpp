// vksplat demo: renders the built-in demo scene from an orbit, so a fresh install has something
// to show with no data at all.
#include <cstdio>
#include <memory>

#include "commands.hpp"
#include "number_checks.hpp"
#include "progress.hpp"
#include "vksplat/scene/demo_scene.hpp"
#include "vksplat/io/ply.hpp"
#include "vksplat/jobs/render_views.hpp"

namespace vksplat::cli {
namespace {

struct DemoArgs {
    GpuOptions gpu;
    std::string out;
    int views = 12;
    int width = 640, height = 480;
    bool force = false;
};

int run_demo(const DemoArgs& args) {
    const GaussianCloud cloud = make_demo_scene();
    const auto cameras = make_orbit_cameras(args.views, args.width, args.height, 4.0, 25.0);
    gpu::Context context(args.gpu.context_options());
    Renderer renderer(context);
    renderer.set_scene(cloud);

    jobs::RenderViewsOptions options;
    options.out_dir = args.out;
    options.settings.background = {1.0f, 1.0f, 1.0f};
    options.mode = args.force ? io::WriteMode::overwrite : io::WriteMode::refuse_existing;
    std::fprintf(stderr, "rendering the demo scene (%zu Gaussians) on %s\n", cloud.size(),
                 context.info().name.c_str());
    ProgressLine progress("rendered");
    ChunkReport chunks;
    const auto result = jobs::render_views(renderer, cameras, options, [&](size_t done, size_t total) {
        chunks.saw(renderer.last_frame().chunks);
        progress.update(done, total);
    });
    chunks.print(context);
    // The scene itself too, so the other commands can be tried on it.
    io::write_ply(cloud, options.out_dir / "demo.ply", options.mode);
    double total_ms = 0;
    for (const auto& v : result.views) total_ms += v.gpu_milliseconds;
    std::printf("wrote %zu views and demo.ply to %s (%.2f ms GPU time per view)\n", result.views.size(),
                args.out.c_str(), result.views.empty() ? 0.0 : total_ms / double(result.views.size()));
    return 0;
}

}  // namespace

void register_demo(CLI::App& app, Action& action) {
    auto* command = app.add_subcommand("demo", "render the built-in demo scene from an orbit");
    command->footer("Example:\n  vksplat demo --out demo_out --views 24 --width 800 --height 600");
    auto args = std::make_shared<DemoArgs>();
    command->add_option("--out", args->out, "output folder")->required();
    command->add_option("--views", args->views, "cameras on the orbit")->check(count_in(1, 3600));
    command->add_option("--width", args->width, "image width")->check(count_in(1, 16384));
    command->add_option("--height", args->height, "image height")->check(count_in(1, 16384));
    command->add_flag("--force", args->force, "overwrite existing output files");
    add_gpu_options(*command, args->gpu);
    command->callback([&action, args] { action = [args] { return run_demo(*args); }; });
}

}  // namespace vksplat::cli
