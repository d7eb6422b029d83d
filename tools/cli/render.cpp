// vksplat render: renders a scene from a camera file into a folder, with metrics given photos.
#include <cstdio>
#include <memory>

#include "commands.hpp"
#include "number_checks.hpp"
#include "progress.hpp"
#include "vksplat/io/cameras.hpp"
#include "vksplat/jobs/render_views.hpp"
#include "vksplat/jobs/view_selection.hpp"

namespace vksplat::cli {
namespace {

struct RenderArgs {
    GpuOptions gpu;
    std::string scene, cameras, out, views, images;
    std::vector<float> background{0, 0, 0};
    int sh_degree = 3;
    int bit_depth = 8;
    bool depth = false, alpha = false, force = false;
};

int run_render(const RenderArgs& args) {
    std::vector<std::string> warnings;
    const GaussianCloud cloud = read_scene_file(args.scene);
    const auto cameras = io::read_cameras(args.cameras, &warnings);
    for (const auto& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());

    gpu::Context context(args.gpu.context_options());
    Renderer renderer(context);
    const SanitizeReport report = renderer.set_scene(cloud);
    if (report.changed()) std::fprintf(stderr, "sanitised %s: %s\n", args.scene.c_str(), report.summary().c_str());

    jobs::RenderViewsOptions options;
    options.out_dir = args.out;
    options.views = jobs::parse_view_list(args.views, cameras.size());
    options.settings.background = {args.background[0], args.background[1], args.background[2]};
    options.settings.max_sh_degree = args.sh_degree;
    options.bit_depth = args.bit_depth;
    options.write_alpha = args.alpha;
    options.write_depth = args.depth;
    if (!args.images.empty()) options.images_dir = args.images;
    options.mode = args.force ? io::WriteMode::overwrite : io::WriteMode::refuse_existing;
    options.inputs = {args.scene, args.cameras};

    std::fprintf(stderr, "rendering %zu Gaussians on %s\n", renderer.scene_size(), context.info().name.c_str());
    ProgressLine progress("rendered");
    ChunkReport chunks;
    const auto result = jobs::render_views(renderer, cameras, options, [&](size_t done, size_t total) {
        chunks.saw(renderer.last_frame().chunks);
        progress.update(done, total);
    });
    chunks.print(context);
    std::printf("wrote %zu views (%zu files) to %s\n", result.views.size(), result.files.size(), args.out.c_str());
    if (result.has_metrics)
        std::printf("mean PSNR %.3f dB, mean SSIM %.4f over %zu views (%s)\n", result.mean_psnr, result.mean_ssim,
                    result.views.size(), result.metrics_csv.c_str());
    return 0;
}

}  // namespace

void register_render(CLI::App& app, Action& action) {
    auto* command = app.add_subcommand("render", "render a scene from a set of cameras");
    command->footer(
        "Example:\n  vksplat render lego/point_cloud.ply --cameras lego/cameras.json --out renders \\\n"
        "      --views 0-12 --background 1,1,1 --images lego/images\n"
        "Files are named after the cameras' images: x.png (x.alpha.png, x.depth.npy). Where two cameras\n"
        "give one name (x.jpg twice, or a/x.jpg and b/x.jpg), the first in the camera file keeps x.png and\n"
        "the next get x-2.png, x-3.png, ..., whichever views are rendered.");
    auto args = std::make_shared<RenderArgs>();
    command->add_option("scene", args->scene, "scene file (any format vksplat reads)")->required()->check(CLI::ExistingFile);
    command->add_option("--cameras", args->cameras, "cameras.json, transforms.json or a COLMAP sparse folder")
        ->required()
        ->check(CLI::ExistingPath);
    command->add_option("--out", args->out, "output folder")->required();
    command->add_option("--views", args->views, "views to render, e.g. 0,3,5-7 (default: all)");
    command->add_option("--background", args->background, "background colour R,G,B in [0,1]")
        ->delimiter(',')
        ->expected(3)
        ->check(number_in(0.0, 1.0));
    command->add_option("--sh-degree", args->sh_degree, "highest SH degree to evaluate")->check(count_in(0, 3));
    command->add_option("--bit-depth", args->bit_depth, "PNG bit depth")->check(CLI::IsMember({8, 16}));
    command->add_option("--images", args->images, "photos to compare with (writes metrics.csv)")
        ->check(CLI::ExistingDirectory);
    command->add_flag("--depth", args->depth, "also write <name>.depth.npy (float32, H x W)");
    command->add_flag("--alpha", args->alpha, "also write <name>.alpha.png (16-bit grey)");
    command->add_flag("--force", args->force, "overwrite existing output files");
    add_gpu_options(*command, args->gpu);
    command->callback([&action, args] { action = [args] { return run_render(*args); }; });
}

}  // namespace vksplat::cli
