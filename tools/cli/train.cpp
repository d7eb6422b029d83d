// vksplat train: trains a scene from photos with the 3DGS recipe on the GPU (jobs::train_scene).
#include <cstdio>
#include <memory>
#include <optional>
#include <unistd.h>

#include "commands.hpp"
#include "interrupt.hpp"
#include "number_checks.hpp"
#include "vksplat/error.hpp"
#include "vksplat/jobs/train_scene.hpp"

namespace vksplat::cli {
namespace {

struct TrainArgs {
    GpuOptions gpu;
    std::string data, out;
    uint64_t iterations = 30000, test_every = 8, checkpoint_every = 5000, seed = 0;
    std::optional<uint64_t> densify_until;
    double grad_threshold = train::DensifyRules{}.grad_threshold;
    size_t max_gaussians = 0;
    size_t random_points = jobs::TrainRecipe{}.random_points;
    std::string strategy = "automatic";
    std::optional<double> budget_peak;
    double keep_share = jobs::LeanRecipe{}.keep_share;
    uint64_t evaluate_every = 0;
    double resolution_scale = 1.0;
    bool white_background = false, resume = false, force = false, quiet = false, profile = false;
    GradientSumsArgs sums;
};

int run_train(const TrainArgs& args) {
    jobs::TrainOptions options;
    options.recipe.iterations = args.iterations;
    options.recipe.test_every = args.test_every;
    options.recipe.densify.max_gaussians = args.max_gaussians;
    options.recipe.random_points = args.random_points;
    options.recipe.strategy = jobs::parse_densify_strategy(args.strategy);
    if (args.budget_peak) options.recipe.budget.ask_peak(*args.budget_peak);
    options.recipe.lean.keep_share = args.keep_share;
    options.evaluate_every = args.evaluate_every;
    // One option for the window of whichever recipe runs; each has its own default.
    if (args.densify_until)
        options.recipe.densify_until = options.recipe.budget.densify_until = options.recipe.lean.densify_until =
            *args.densify_until;
    options.recipe.densify.grad_threshold = args.grad_threshold;
    options.background = args.white_background ? std::array<float, 3>{1, 1, 1} : std::array<float, 3>{0, 0, 0};
    options.seed = args.seed;
    options.memory_budget = static_cast<uint64_t>(args.gpu.memory_budget_mb * 1048576.0);
    options.out_dir = args.out;
    options.mode = args.force ? io::WriteMode::overwrite : io::WriteMode::refuse_existing;
    options.checkpoint_every = args.checkpoint_every;
    options.resume = args.resume;
    options.stop = &stop_on_interrupt();
    options.notice = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };

    const jobs::TrainingData data =
        jobs::load_training_data(args.data, options.recipe, args.resolution_scale, args.seed);
    for (const auto& w : data.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    for (const auto& notice : data.notices) std::fprintf(stderr, "%s\n", notice.c_str());
    gpu::Context context(args.gpu.context_options());
    options.deterministic = args.sums.fixed_point(context);
    Renderer renderer(context);
    RenderSettings settings;
    settings.background = options.background;
    const auto measure = [&](const GaussianCloud& scene, const eval::TestViews& views) {
        return eval::measure_quality(renderer, scene, views, settings, true);
    };
    std::fprintf(stderr, "training from %s (%s: %zu training, %zu test views, %zu starting points) on %s\n",
                 args.data.c_str(), data.format.c_str(), data.train_views.size(), data.test_views.size(),
                 data.initial.size(), context.info().name.c_str());
    const bool terminal = isatty(STDERR_FILENO) && !args.quiet;
    const auto result = jobs::train_scene(
        context, data, jobs::photos_in_folder(data.images_dir, options.background, args.resolution_scale,
                                             data.undistortion), options,
        measure, [&](const train::LoopStatus& s) {
            if (args.quiet && s.iteration != s.iterations) return;
            std::fprintf(stderr, "%siteration %llu/%llu  %zu Gaussians  loss %.4f  train PSNR %.2f dB  %.0f s, %.0f s left%s",
                         terminal ? "\r" : "", static_cast<unsigned long long>(s.iteration),
                         static_cast<unsigned long long>(s.iterations), s.gaussians, s.loss, s.psnr, s.seconds,
                         s.seconds_left, terminal && s.iteration != s.iterations ? "   " : "\n");
            std::fflush(stderr);
        });
    if (result.interrupted) {
        std::fprintf(stderr, "\ninterrupted at iteration %llu: state saved in %s/checkpoint (--resume continues)\n",
                     static_cast<unsigned long long>(result.iterations), args.out.c_str());
        return 130;
    }
    std::printf("trained %llu iterations (%llu skipped) in %.1f s, GPU %.3f ms per iteration; %zu Gaussians; "
                "peak device memory %.1f MB\n",
                static_cast<unsigned long long>(result.iterations), static_cast<unsigned long long>(result.skipped),
                result.seconds, result.gpu_ms_per_iteration, result.gaussians, double(result.peak_device_bytes) / 1e6);
    if (args.profile) {
        std::printf("GPU time per step by pass (medians):");
        for (const auto& stage : result.stages) std::printf("  %s %.3f ms", stage.stage.c_str(), stage.milliseconds);
        std::printf("\n");
        std::printf("host time of scene changes: %s\n", train::describe(result.scene_changes).c_str());
    }
    if (result.importance_prunes.prune_events > 0)
        std::printf("%s recipe: %zu Gaussians removed by blend weight in %llu prunes (%.1f s scoring)\n",
                    result.strategy.c_str(), result.importance_prunes.pruned,
                    static_cast<unsigned long long>(result.importance_prunes.prune_events),
                    result.importance_prunes.importance_seconds);
    if (result.mcmc_events.relocated + result.mcmc_events.added > 0)
        std::printf("mcmc recipe: %zu transparent Gaussians moved, %zu added\n", result.mcmc_events.relocated,
                    result.mcmc_events.added);
    if (result.test.psnr.empty())
        std::printf("test views: none held out, so no test PSNR or SSIM\n");
    else
        std::printf("test views (%zu): PSNR %.3f dB, SSIM %.4f\n", result.test.psnr.size(), result.test.mean_psnr,
                    result.test.mean_ssim);
    std::printf("wrote %s, %s, %s, %s\n", result.ply.string().c_str(), result.cameras_json.string().c_str(),
                result.metrics_json.string().c_str(), result.report.string().c_str());
    return 0;
}

}  // namespace

void register_train(CLI::App& app, Action& action) {
    auto* command = app.add_subcommand("train", "train a scene from photos (the 3DGS recipe, on the GPU)");
    command->footer(
        "DATA: a COLMAP folder (sparse/0 with points3D.bin/.txt/.ply, images/), a NeRF-synthetic folder\n"
        "(transforms_train.json, transforms_test.json) or an INRIA cameras.json beside images/.\n"
        "Writes OUT_DIR/point_cloud.ply, cameras.json (with each camera's split), metrics.json (with the count over\n"
        "the run), report.html (its charts), checkpoint.\n"
        "Example:\n  vksplat train bonsai --max-gaussians 400000 -o bonsai_trained");
    auto args = std::make_shared<TrainArgs>();
    command->add_option("data", args->data, "the data folder")->required()->check(CLI::ExistingDirectory);
    command->add_option("-o,--out", args->out, "output folder")->required();
    command->add_option("--iters", args->iterations, "iterations (default 30000)")->check(count_in(1));
    command->add_option("--max-gaussians", args->max_gaussians,
                        "train to at most this many Gaussians; with --strategy automatic the budget recipe, "
                        "which grows to reach it at --densify-until (a random subset of the starting points "
                        "when they would fill more than half of it)")
        ->check(count_in(1));
    command->add_option("--strategy", args->strategy,
                        "how Gaussians grow: lean (the 3DGS recipe's growth until --densify-until, then only the "
                        "Gaussians that carry --keep-share of the blend weight train on), budget (needs "
                        "--max-gaussians), mcmc (3DGS-MCMC's relocation to --max-gaussians), reference (the 3DGS "
                        "recipe; --max-gaussians then only caps it) or automatic (budget when --max-gaussians is "
                        "given, else lean)")
        ->capture_default_str()
        ->check(CLI::IsMember({"automatic", "reference", "lean", "budget", "mcmc"}));
    command->add_option("--keep-share", args->keep_share,
                        "lean recipe: keep the fewest Gaussians that carry this share of the blend weight over the "
                        "training views (1: all that carry any)")
        ->capture_default_str()
        ->check(number_in(1e-6, 1.0));
    command->add_option("--budget-peak", args->budget_peak,
                        "budget recipe: grow to this multiple of --max-gaussians, then keep the budget's most "
                        "important (1: grow to the budget only, better where a scene over-fits; default 3, but "
                        "to no more than " + std::to_string(train::BudgetSchedule{}.peak_limit) + " Gaussians)")
        ->check(number_in(1.0, 100.0));
    command->add_option("--evaluate-every", args->evaluate_every,
                        "measure the test views every N iterations into metrics.json's history (0: at the end only)")
        ->check(count_in(0));
    command->add_option("--random-points", args->random_points,
                        "NeRF-synthetic and INRIA folders, which have no SfM points: start from this many random "
                        "points (in the scene's box, or in what the cameras see together)")
        ->capture_default_str()
        ->check(count_in(1));
    command->add_option("--resolution-scale", args->resolution_scale, "train at this fraction of the photos' size")
        ->check(number_in(0.01, 1.0));
    command->add_option("--densify-until", args->densify_until,
                        "last iteration that clones, splits and prunes (0: never densify; default 15000 for the "
                        "reference recipe, 5000 for the lean and budget recipes)")
        ->check(count_in(0));
    command->add_option("--densify-grad-threshold", args->grad_threshold,
                        "mean NDC gradient of a Gaussian's projected mean above which it is cloned or split")
        ->capture_default_str()
        ->check(positive_number());
    command->add_flag("--white-background", args->white_background, "white instead of black behind the scene");
    command->add_option("--test-every", args->test_every,
                        "COLMAP: every N-th photo by name is a test view (default 8; 0: none held out)")
        ->check(count_in(0));
    command->add_option("--checkpoint-every", args->checkpoint_every, "iterations between checkpoints")
        ->check(count_in(1));
    command->add_option("--seed", args->seed, "seed of the view order and random starts")->check(count_in(0));
    command->add_flag("--resume", args->resume, "continue from OUT_DIR/checkpoint");
    add_gradient_sums_flags(*command, args->sums);
    command->add_flag("--quiet", args->quiet, "no progress lines (for logs)");
    command->add_flag("--profile", args->profile,
                      "print each pass's median GPU time per step (Vulkan timestamps) and where densification's host "
                      "time went (metrics.json has both always)");
    command->add_flag("--force", args->force, "overwrite existing outputs");
    add_gpu_options(*command, args->gpu);
    command->callback([&action, args] { action = [args] { return run_train(*args); }; });
}

}  // namespace vksplat::cli
