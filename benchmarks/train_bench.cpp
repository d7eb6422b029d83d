// train_bench: the training job (jobs::train_scene, what `vksplat train` runs) on a GPU host that
// has a Vulkan driver and no image codecs. Cameras, split and starting points come from the data
// folder as `vksplat train` reads it; the photos come as <name>.npy (uint8 [H, W, 3], made there by
// benchmarks/photos_to_npy.py). Prints progress, the test PSNR, time, Gaussians and peak device
// memory, and with --renders writes each test view's render as float32 .npy so that
// benchmarks/test_view_metrics.py can score SSIM the reference's way.
//
//   train_bench bonsai --photos npy/ --out run/ --max-gaussians 400000
//   train_bench lego --photos npy/ --out run/ --background 1,1,1
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <optional>

#include "vksplat/error.hpp"
#include "vksplat/eval/metrics.hpp"
#include "vksplat/io/npy.hpp"
#include "vksplat/jobs/train_scene.hpp"
#include "vksplat/render/renderer.hpp"

#include "npy_photo.hpp"

using namespace vksplat;
using bench::read_npy_photo;

int main(int argc, char** argv) {
    CLI::App app{"train_bench: train a scene from photos on the GPU and report quality, time and memory"};
    std::string data_dir, photos_dir, out_dir, renders_dir, device;
    std::vector<float> background{0, 0, 0};
    jobs::TrainRecipe recipe;
    size_t max_gaussians = 0;
    app.add_option("data", data_dir, "COLMAP, NeRF-synthetic or INRIA folder, as vksplat train takes")->required();
    app.add_option("--photos", photos_dir, "folder of <image name>.npy, uint8 [H, W, 3]")->required();
    app.add_option("--out", out_dir, "output folder (point_cloud.ply, metrics.json, ...)")->required();
    app.add_option("--renders", renders_dir, "write the test views' renders here as float32 .npy");
    app.add_option("--background", background)->delimiter(',')->expected(3);
    app.add_option("--iters", recipe.iterations);
    app.add_option("--max-gaussians", max_gaussians);
    std::optional<uint64_t> densify_until;
    app.add_option("--densify-until", densify_until, "the window of whichever recipe runs");
    app.add_option("--grad-threshold", recipe.densify.grad_threshold);
    app.add_option("--max-screen-radius", recipe.densify.max_screen_radius,
                   "> 0: after the first opacity reset, also prune radii above it (pixels)");
    app.add_option("--opacity-reset-interval", recipe.opacity_reset_interval);
    app.add_option("--densify-interval", recipe.densify_interval, "steps between densifications (the reference's 100)")
        ->check(CLI::PositiveNumber);
    std::string strategy = "automatic", ranking = "mean";
    uint64_t evaluate_every = 0;
    app.add_option("--strategy", strategy, "automatic, reference, lean, budget or mcmc");
    app.add_option("--mcmc-noise", recipe.mcmc.position_noise);
    app.add_option("--mcmc-opacity-reg", recipe.mcmc.opacity_regularization);
    app.add_option("--mcmc-scale-reg", recipe.mcmc.scale_regularization);
    app.add_option("--mcmc-growth", recipe.mcmc.growth);
    app.add_option("--mcmc-until", recipe.mcmc.refine_until);
    app.add_option("--mcmc-start-opacity", recipe.mcmc.start_opacity);
    app.add_option("--mcmc-start-scale", recipe.mcmc.start_scale);
    app.add_option("--growth-exponent", recipe.budget.growth_exponent);
    app.add_option("--reach", recipe.budget.reach);
    app.add_option("--ranking", ranking, "mean or sum (of the densification gradient)");
    app.add_option("--min-gradient", recipe.budget.min_gradient);
    app.add_option("--prune-ratio", recipe.budget.prune_ratio);
    app.add_option("--start-fraction", recipe.start_fraction);
    std::optional<double> peak;
    app.add_option("--peak", peak,
                   "grow to peak x budget, prune to the budget at --densify-until (as train --budget-peak)");
    app.add_option("--others-final", recipe.rates.others_final,
                   "the rates but position's decay to this multiple of themselves by the end");
    app.add_option("--settle-rounds", recipe.budget.settle.rounds, "settle in this many rounds");
    app.add_option("--settle-spacing", recipe.budget.settle.spacing, "steps between settling rounds");
    app.add_option("--keep-share", recipe.lean.keep_share,
                   "the lean recipe settles to the Gaussians carrying this share of the blend weight");
    app.add_option("--restart-decay", recipe.budget.settle.restart_decay,
                   "true: the position rate decays afresh from the settling on (the default)");
    app.add_flag("--budget-resets", recipe.budget.reset_opacity,
                 "the budget recipe resets opacities on the reference's schedule (off by default)");
    app.add_flag("--budget-prune-large", recipe.budget.prune_large,
                 "the budget recipe prunes the world-large Gaussians as the reference does (off by default)");
    app.add_flag("--budget-sampling", recipe.budget_sampling,
                 "the budget recipe removes a weighted random sample by blend weight, not the least");
    std::string budget_score = std::string(prune::to_string(recipe.budget_score));
    app.add_option("--budget-score", budget_score, "the budget recipe's ranking (a prune --method)");
    app.add_option("--evaluate-every", evaluate_every, "test PSNR every N iterations into metrics.json's history");
    bool deterministic = false, fast_sums = false;
    auto* deterministic_flag = app.add_flag("--deterministic", deterministic,
                                            "fixed-point gradient sums (train --deterministic; train's default where the "
                                            "device has 64-bit atomics)");
    app.add_flag("--fast-sums", fast_sums, "float-atomic gradient sums (train --fast-sums)")->excludes(deterministic_flag);
    std::string blend_backward = "fastest";
    app.add_option("--blend-backward", blend_backward,
                   "fastest (time both forms on the first steps, keep the faster), per-pixel or per-splat")
        ->check(CLI::IsMember({"fastest", "per-pixel", "per-splat"}));
    app.add_option("--device", device);
    bool pipeline_stats = false;
    app.add_flag("--pipeline-stats", pipeline_stats,
                 "print what the driver says of the training passes' pipelines (registers, shared memory, ...)");
    CLI11_PARSE(app, argc, argv);
    if (peak) recipe.budget.ask_peak(*peak);
    try {
        recipe.densify.max_gaussians = max_gaussians;
        if (densify_until) recipe.densify_until = recipe.budget.densify_until = recipe.lean.densify_until = *densify_until;
        recipe.strategy = jobs::parse_densify_strategy(strategy);
        recipe.budget_score = prune::parse_score_method(budget_score);
        if (ranking != "mean" && ranking != "sum") throw InputError("--ranking " + ranking, "choose mean or sum");
        recipe.budget.ranking = ranking == "sum" ? train::DensifyRanking::gradient_sum : train::DensifyRanking::mean_gradient;
        gpu::Context context(gpu::ContextOptions{device, false, 0, pipeline_stats});
        const jobs::TrainingData data = jobs::load_training_data(data_dir, recipe, 1.0, 0);
        for (const auto& w : data.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
        std::printf("%s (%s): %zu cameras (%zu train, %zu test), %zu starting points, on %s\n", data_dir.c_str(),
                    data.format.c_str(), data.cameras.size(), data.train_views.size(), data.test_views.size(),
                    data.initial.size(), context.info().name.c_str());
        std::fflush(stdout);

        jobs::TrainOptions options;
        options.recipe = recipe;
        options.background = {background[0], background[1], background[2]};
        options.out_dir = out_dir;
        options.checkpoint_every = recipe.iterations + 1;  // timing the steps, not the disk
        options.evaluate_every = evaluate_every;
        // As `vksplat train` decides, so that the bench times the sums the command runs.
        options.deterministic = train::fixed_point_sums(context, deterministic, fast_sums);
        std::printf("gradients summed %s\n", options.deterministic ? "in fixed point" : "with float atomics");
        options.blend_backward = blend_backward == "per-pixel"   ? train::BlendBackward::per_pixel
                                 : blend_backward == "per-splat" ? train::BlendBackward::per_splat
                                                                 : train::BlendBackward::fastest;
        RenderSettings settings;
        settings.background = options.background;
        const jobs::TestMeasure measure = [&](const GaussianCloud& scene, const eval::TestViews& views) {
            Renderer renderer(context);
            renderer.set_scene(scene);
            eval::Quality quality;
            for (size_t v = 0; v < views.cameras.size(); ++v) {
                const RenderOutput out = renderer.render(views.cameras[v], settings);
                quality.psnr.push_back(eval::psnr(out.rgb.data(), views.targets[v].data(), out.width, out.height));
                quality.mean_psnr += quality.psnr.back() / double(views.cameras.size());
                if (!renders_dir.empty()) {
                    std::filesystem::create_directories(renders_dir);
                    const auto stem = std::filesystem::path(views.cameras[v].name).stem().string();
                    io::write_npy(std::filesystem::path(renders_dir) / (stem + ".npy"), out.rgb.data(),
                                  {size_t(out.height), size_t(out.width), 3}, io::WriteMode::overwrite);
                }
            }
            return quality;
        };
        const auto progress = [last = -1.0](const train::LoopStatus& s) mutable {
            if (s.seconds - last < 10.0 && s.iteration != s.iterations) return;
            last = s.seconds;
            std::printf("  iteration %6llu: %8zu Gaussians, loss %.4f, train PSNR %.2f dB, %.1f s, ETA %.0f s\n",
                        static_cast<unsigned long long>(s.iteration), s.gaussians, s.loss, s.psnr, s.seconds,
                        s.seconds_left);
            std::fflush(stdout);
        };
        const jobs::PhotoSource photos = [&](const Camera& c) { return read_npy_photo(photos_dir, c); };
        options.notice = [](const std::string& line) { std::printf("%s\n", line.c_str()); };
        const jobs::TrainResult result = jobs::train_scene(context, data, photos, options, measure, progress);
        std::printf("trained %llu iterations (skipped %llu) in %.1f s (densification %.1f s): %zu Gaussians, GPU median %.3f ms per "
                    "iteration, peak device memory %.1f MB, scene extent %.3f\n",
                    static_cast<unsigned long long>(result.iterations), static_cast<unsigned long long>(result.skipped),
                    result.seconds, result.strategy_seconds, result.gaussians, result.gpu_ms_per_iteration,
                    double(result.peak_device_bytes) / 1e6, result.scene_extent);
        std::printf("scene changes (host wall): %s\n", train::describe(result.scene_changes).c_str());
        std::printf("GPU time per step by pass (medians):");
        for (const auto& stage : result.stages) std::printf("  %s %.3f ms", stage.stage.c_str(), stage.milliseconds);
        std::printf("\n");
        std::printf("strategy %s: %zu pruned by importance in %llu events (%.1f s scoring)\n", result.strategy.c_str(),
                    result.importance_prunes.pruned, static_cast<unsigned long long>(result.importance_prunes.prune_events),
                    result.importance_prunes.importance_seconds);
        if (recipe.strategy == jobs::DensifyStrategy::mcmc)
            std::printf("mcmc: %zu relocated, %zu added\n", result.mcmc_events.relocated, result.mcmc_events.added);
        std::printf("test PSNR (%zu views): %.3f dB\n", result.test.psnr.size(), result.test.mean_psnr);
        for (const auto& pipeline : context.pipeline_statistics()) {
            std::printf("pipeline %s:", pipeline.pipeline.c_str());
            for (const auto& [name, value] : pipeline.values) std::printf("  %s %s", name.c_str(), value.c_str());
            std::printf("\n");
        }
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
