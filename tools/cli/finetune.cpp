// vksplat finetune: re-fits a scene (a pruned one, typically) to its photos on the GPU.
#include <cstdio>
#include <memory>
#include <unistd.h>

#include "commands.hpp"
#include "interrupt.hpp"
#include "number_checks.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/cameras.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/jobs/finetune.hpp"
#include "vksplat/jobs/prune_scene.hpp"
#include "vksplat/jobs/view_selection.hpp"

namespace vksplat::cli {
namespace {

struct FinetuneArgs {
    GpuOptions gpu;
    std::string scene, cameras, images, out, test_views, train_views, checkpoint;
    std::optional<uint64_t> iterations;  // unset: 5000, unless --seconds
    std::optional<double> seconds;
    uint64_t checkpoint_every = 1000, seed = 0;
    std::vector<float> background{0, 0, 0};
    std::string position_lr = "final";
    bool resume = false, force = false, quiet = false;
    GradientSumsArgs sums;
};

void print_status(const train::LoopStatus& s, bool terminal) {
    std::fprintf(stderr, "%siteration %llu/%llu  loss %.4f  train PSNR %.2f dB  %zu Gaussians  %.0f s, %.0f s left%s",
                 terminal ? "\r" : "", static_cast<unsigned long long>(s.iteration),
                 static_cast<unsigned long long>(s.iterations), s.loss, s.psnr, s.gaussians, s.seconds, s.seconds_left,
                 terminal && s.iteration != s.iterations ? "   " : "\n");
    std::fflush(stderr);
}

int run_finetune(const FinetuneArgs& args) {
    if (args.iterations && args.seconds)
        throw InputError("--seconds", "is a budget instead of an iteration count: give --iters or --seconds, not both");
    std::vector<std::string> notes;
    const GaussianCloud cloud = read_scene_file(args.scene);
    const auto cameras = io::read_cameras(args.cameras, &notes);

    jobs::FinetuneOptions options;
    options.iterations = args.iterations.value_or(options.iterations);
    options.seconds = args.seconds;
    if (!args.test_views.empty()) options.test_views = jobs::parse_view_list(args.test_views, cameras.size());
    if (!args.train_views.empty()) options.train_views = jobs::parse_view_list(args.train_views, cameras.size());
    options.train.background = {args.background[0], args.background[1], args.background[2]};
    options.seed = args.seed;
    if (args.position_lr == "decay") options.train.position_schedule = train::PositionSchedule::decay;
    options.checkpoint = args.checkpoint.empty() ? std::filesystem::path(args.out + ".checkpoint")
                                                 : std::filesystem::path(args.checkpoint);
    options.checkpoint_every = args.checkpoint_every;
    options.resume = args.resume;
    options.stop = &stop_on_interrupt();
    options.out = args.out;
    options.mode = args.force ? io::WriteMode::overwrite : io::WriteMode::refuse_existing;
    options.inputs = {args.scene, args.cameras};
    options.source = "finetune of " + args.scene;
    options.notice = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
    jobs::ViewSplit split = jobs::split_views(cameras, options.test_views, options.train_views);
    options.test_views = std::move(split.test);
    options.train_views = std::move(split.train);
    std::vector<Camera> test_cameras;
    for (size_t v : options.test_views) test_cameras.push_back(cameras[v]);

    gpu::Context context(args.gpu.context_options());
    options.train.deterministic = args.sums.fixed_point(context);
    Renderer renderer(context);
    RenderSettings settings;
    settings.background = options.train.background;
    const auto photos = jobs::photos_in_folder(args.images, options.train.background);
    const eval::TestViews views = eval::photo_targets(test_cameras, args.images, options.train.background);
    const jobs::QualityProbe quality = [&](const GaussianCloud& scene) {
        return eval::measure_quality(renderer, scene, views, settings, true);
    };

    const bool terminal = isatty(STDERR_FILENO) && !args.quiet;
    if (args.seconds)
        std::fprintf(stderr, "re-fitting %zu Gaussians on %s for %g s\n", cloud.size(), context.info().name.c_str(),
                     *args.seconds);
    else
        std::fprintf(stderr, "re-fitting %zu Gaussians on %s: %llu iterations\n", cloud.size(),
                     context.info().name.c_str(), static_cast<unsigned long long>(options.iterations));
    const auto result = jobs::finetune_scene(context, cloud, cameras, photos, options, quality,
                                             [&](const train::LoopStatus& s) {
                                                 if (!args.quiet || s.iteration == s.iterations) print_status(s, terminal);
                                             });
    if (result.sanitize.changed())
        std::fprintf(stderr, "sanitised %s: %s\n", args.scene.c_str(), result.sanitize.summary().c_str());
    if (result.interrupted) {
        std::fprintf(stderr, "\ninterrupted at iteration %llu: state saved in %s (--resume continues); %s not written\n",
                     static_cast<unsigned long long>(result.iterations), options.checkpoint.string().c_str(),
                     args.out.c_str());
        return 130;
    }
    std::printf("iterations: %llu (%llu skipped for non-finite gradients), %.1f s, GPU %.3f ms per iteration\n",
                static_cast<unsigned long long>(result.iterations), static_cast<unsigned long long>(result.skipped),
                result.seconds, result.gpu_ms_per_iteration);
    if (args.seconds)
        std::printf("budget: %g s, in which %llu iterations were planned from the steps timed first\n", *args.seconds,
                    static_cast<unsigned long long>(result.planned_iterations));
    for (const auto& stage : result.stages) std::printf("    %-20s %.3f ms\n", stage.stage.c_str(), stage.milliseconds);
    const size_t n = result.test_views.size();
    const char* held = result.held_out ? "" : ", also trained on: not held out";
    if (result.before)
        std::printf("test views (%zu%s) against the photos: PSNR %.3f -> %.3f dB, SSIM %.4f -> %.4f\n", n, held,
                    result.before->mean_psnr, result.after->mean_psnr, result.before->mean_ssim,
                    result.after->mean_ssim);
    else if (result.after)
        std::printf("test views (%zu%s) against the photos: PSNR %.3f dB, SSIM %.4f\n", n, held,
                    result.after->mean_psnr, result.after->mean_ssim);
    std::printf("device memory: %.1f MB\nwrote %s\n", double(result.device_bytes) / 1e6, args.out.c_str());
    return 0;
}

}  // namespace

void register_finetune(CLI::App& app, Action& action) {
    auto* command = app.add_subcommand("finetune", "re-fit a scene's Gaussians to its photos (Adam on the GPU)");
    command->footer(
        "The reference trainer's loss (0.8 L1 + 0.2 D-SSIM) and learning rates, the position rate at its\n"
        "final value; one random training view per step; the test views are not trained on (unless the\n"
        "cameras leave no others: the run then says so) and are measured before and after.\n"
        "A checkpoint (OUT.checkpoint unless --checkpoint) is kept every --checkpoint-every iterations\n"
        "and on Ctrl-C; --resume continues from it, and only from a checkpoint of the same scene,\n"
        "cameras and recipe. A checkpoint path is never the input or the output nor any other file;\n"
        "an earlier run's checkpoint is replaced only with --force. No input is ever written over.\n"
        "Example:\n  vksplat finetune lego_half.ply --cameras lego/cameras.json --images lego/images \\\n"
        "      --background 1,1,1 --iters 5000 -o lego_half_refit.ply");
    auto args = std::make_shared<FinetuneArgs>();
    command->add_option("scene", args->scene, "scene file (any format vksplat reads)")->required()->check(CLI::ExistingFile);
    command->add_option("--cameras", args->cameras, "cameras.json, transforms.json or a COLMAP sparse folder")
        ->required()
        ->check(CLI::ExistingPath);
    command->add_option("--images", args->images, "the photos, found by camera name")->required()->check(CLI::ExistingDirectory);
    command->add_option("--iters", args->iterations,
                        "iterations in all (default 5000; a resumed run counts the earlier ones)")
        ->check(count_in(1));
    command->add_option("--seconds", args->seconds,
                        "instead of --iters: re-fit for S seconds of wall time (a few steps timed first set the\n"
                        "count, so that the position rate's decay ends with the time)");
    command->add_option("--test-views", args->test_views,
                        "held-out views, e.g. 0-12 (default: the cameras' test split, else the first 13 if there are more, else all)");
    command->add_option("--train-views", args->train_views, "views to train on (default: all but the test views)");
    command->add_option("--background", args->background, "background colour R,G,B in [0,1] (also under photo alpha)")
        ->delimiter(',')
        ->expected(3)
        ->check(number_in(0.0, 1.0));
    command->add_option("--seed", args->seed, "seed of the training views' order")->check(count_in(0));
    command->add_option("--position-lr", args->position_lr,
                        "final: the reference's final position rate throughout (default); decay: from its\n"
                        "initial to its final rate over the run, as a fresh training does")
        ->check(CLI::IsMember({"final", "decay"}));
    command->add_option("--checkpoint", args->checkpoint, "checkpoint file (default: OUT.checkpoint)");
    command->add_option("--checkpoint-every", args->checkpoint_every, "iterations between checkpoints")
        ->check(count_in(1));
    command->add_flag("--resume", args->resume, "continue from the checkpoint");
    add_gradient_sums_flags(*command, args->sums);
    command->add_flag("--quiet", args->quiet, "no progress lines (for logs)");
    command->add_option("-o,--out", args->out, "re-fitted scene (.ply, .compressed.ply, .splat or .spz)")->required();
    command->add_flag("--force", args->force, "overwrite an existing output");
    add_gpu_options(*command, args->gpu);
    command->callback([&action, args] { action = [args] { return run_finetune(*args); }; });
}

}  // namespace vksplat::cli
