// vksplat prune: scores the Gaussians of a scene over its training views and writes a smaller scene.
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include "commands.hpp"
#include "number_checks.hpp"
#include "progress.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/io/cameras.hpp"
#include "vksplat/io/ply.hpp"
#include "vksplat/jobs/prune_scene.hpp"
#include "vksplat/jobs/view_selection.hpp"

namespace vksplat::cli {
namespace {

struct PruneArgs {
    GpuOptions gpu;
    std::string scene, cameras, out, method, images, test_views, train_views;
    std::string save_scores, save_totals, load_scores;
    std::optional<float> threshold;
    std::optional<double> ratio, max_psnr_drop, max_mb;
    std::optional<size_t> keep;
    bool allow_sh_reduction = false;
    std::vector<float> background{0, 0, 0};
    std::optional<int> sh_degree;
    std::vector<int> sh_bits;  // degree 1, then degrees 2 and 3; empty: full precision
    uint64_t seed = 0;
    std::string recover;  // --recover's N, "auto" without one (by the fraction dropped), empty if not given
    std::optional<double> recover_seconds;
    std::optional<int> rounds;  // default: jobs::recover_rounds's, or 1 with a quality budget (which re-fits each probe once)
    uint64_t round_spacing = jobs::kDefaultRoundSpacing;
    std::string round_keep = "sample";
    std::string position_lr = "decay";
    bool force = false;
    GradientSumsArgs sums;
};

std::optional<std::filesystem::path> optional_path(const std::string& path) {
    if (path.empty()) return std::nullopt;
    return path;
}

jobs::PruneSelector selector(const PruneArgs& args) {
    if (args.threshold) return jobs::DropAtOrBelow{*args.threshold};
    if (args.ratio) return jobs::DropRatio{*args.ratio};
    if (args.keep) return jobs::KeepCount{*args.keep};
    if (args.max_mb) {
        prune::SizeBudget size;
        size.max_bytes = static_cast<size_t>(*args.max_mb * 1e6);  // megabytes of 10^6 bytes, rounded down
        return size;
    }
    prune::QualityBudget budget;
    if (args.max_psnr_drop) budget.max_psnr_drop = *args.max_psnr_drop;
    budget.allow_sh_reduction = args.allow_sh_reduction;
    return budget;
}

void print_probe(const prune::BudgetProbe& probe) {
    std::printf("probe: keep %zu, SH %d", probe.kept, probe.sh_degree);
    if (probe.sh_share > 0) std::printf(" with %.0f%% of the higher bands dropped per Gaussian", 100.0 * probe.sh_share);
    if (probe.sh_precision != prune::ShPrecision{})
        std::printf(", SH bits %d,%d", probe.sh_precision.degree1_bits, probe.sh_precision.higher_bits);
    if (probe.bytes > 0) std::printf(", %.3f MB", double(probe.bytes) / 1e6);
    std::printf(": %sPSNR %.3f dB, drop %.3f dB, %.2f s  %s\n", probe.refitted ? "re-fitted (short) " : "", probe.psnr,
                probe.drop, probe.seconds, probe.meets ? "within budget" : "over budget");
    std::fflush(stdout);  // one line per probe as it happens, also when stdout is a pipe
}

void print_result(const jobs::PruneResult& result, const std::string& out) {
    const double kept = result.count_before ? 100.0 * double(result.count_after) / double(result.count_before) : 0.0;
    std::printf("Gaussians: %zu -> %zu (%.1f%% kept", result.count_before, result.count_after, kept);
    if (result.lossless_applied) std::printf("; the lossless pass dropped %zu", result.lossless_dropped);
    std::printf(")\nsize: %zu bytes as PLY -> %zu bytes written (%.2f -> %.2f MB)\nSH degree: %d -> %d",
                result.bytes_before, result.bytes_after, double(result.bytes_before) / 1e6, double(result.bytes_after) / 1e6,
                result.sh_degree_before, result.sh_degree_after);
    if (result.budget && result.budget->sh_share > 0 && result.budget->sh_share < 1)
        std::printf(" (%.0f%% of the higher bands dropped per Gaussian)", 100.0 * result.budget->sh_share);
    if (result.budget && result.budget->sh_precision != prune::ShPrecision{})
        std::printf(", SH bits %d,%d", result.budget->sh_precision.degree1_bits, result.budget->sh_precision.higher_bits);
    std::printf("\n");
    if (result.budget && !result.budget->met)
        std::printf("warning: even all that the lossless pass left misses the budget (drop %.3f dB); kept that\n",
                    result.budget->drop);
    for (size_t r = 0; r < result.recover_rounds.size(); ++r) {
        const auto& round = result.recover_rounds[r];
        if (round.after_fit)
            std::printf("after the fit: %zu Gaussians left, re-fitted %llu iterations in %.1f s\n", round.kept,
                        static_cast<unsigned long long>(round.iterations), round.seconds);
        else
            std::printf("round %zu: pruned to %zu Gaussians and re-fitted, %llu iterations in %.1f s\n", r + 1,
                        round.kept, static_cast<unsigned long long>(round.iterations), round.seconds);
    }
    const size_t views = result.test_views.size();
    if (result.before)
        std::printf("test views (%zu) against the photos: PSNR %.3f -> %.3f dB, SSIM %.4f -> %.4f\n", views,
                    result.before->mean_psnr, result.after.mean_psnr, result.before->mean_ssim, result.after.mean_ssim);
    else
        std::printf("test views (%zu) against the unpruned render: PSNR %.3f dB, SSIM %.4f\n", views,
                    result.after.mean_psnr, result.after.mean_ssim);
    std::printf("wrote %s\n", out.c_str());
}

int run_prune(const PruneArgs& args) {
    std::vector<std::string> warnings;
    const GaussianCloud cloud = read_scene_file(args.scene);
    const auto cameras = io::read_cameras(args.cameras, &warnings);
    for (const auto& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());

    jobs::PruneOptions options;
    if (!args.method.empty()) options.method = prune::parse_score_method(args.method);
    options.selector = selector(args);
    if (!args.test_views.empty()) options.test_views = jobs::parse_view_list(args.test_views, cameras.size());
    if (!args.train_views.empty()) options.train_views = jobs::parse_view_list(args.train_views, cameras.size());
    options.images_dir = optional_path(args.images);
    options.settings.background = {args.background[0], args.background[1], args.background[2]};
    options.sh_degree = args.sh_degree;
    if (!args.sh_bits.empty()) options.sh_precision = prune::ShPrecision{args.sh_bits[0], args.sh_bits[1]};
    options.seed = args.seed;
    options.save_scores = optional_path(args.save_scores);
    options.save_totals = optional_path(args.save_totals);
    options.load_scores = optional_path(args.load_scores);
    options.out = args.out;
    options.mode = args.force ? io::WriteMode::overwrite : io::WriteMode::refuse_existing;
    options.inputs = {args.scene, args.cameras};
    if (!args.recover.empty() || args.recover_seconds) {
        jobs::RecoverOptions recover;
        if (!args.recover.empty() && args.recover != "auto") recover.iterations = std::stoull(args.recover);
        recover.seconds = args.recover_seconds;
        recover.rounds = args.rounds;
        recover.round_spacing = args.round_spacing;
        recover.sampled = args.round_keep == "sample";
        recover.finetune.seed = args.seed;
        if (args.position_lr == "final") recover.finetune.train.position_schedule = train::PositionSchedule::final_rate;
        options.recover = recover;
    }

    gpu::Context context(args.gpu.context_options());
    if (options.recover)
        options.recover->finetune.train.deterministic = args.sums.fixed_point(context);
    Renderer renderer(context);
    std::fprintf(stderr, "pruning %zu Gaussians by %s on %s\n", cloud.size(),
                 std::string(prune::to_string(jobs::score_method_of(options))).c_str(), context.info().name.c_str());
    ProgressLine scoring("scored views");
    jobs::PruneProgress progress;
    ChunkReport chunks;
    progress.scoring = [&](size_t done, size_t total) {
        chunks.saw(renderer.last_frame().chunks);
        scoring.update(done, total);
    };
    progress.probe = [&](const prune::BudgetProbe& probe) {
        chunks.saw(renderer.last_frame().chunks);
        print_probe(probe);
    };
    std::unique_ptr<ProgressLine> refit;
    int refit_round = 0;
    uint64_t refit_iteration = 0;
    progress.refit = [&](int round, const train::LoopStatus& status) {
        // Round 0: a size budget's shortlisted candidates, each re-fitted briefly in turn.
        if (round != refit_round || !refit || status.iteration < refit_iteration) {
            refit_round = round;
            refit = std::make_unique<ProgressLine>(
                round == 0                        ? std::string("short re-fit of a size candidate, iterations")
                : round == jobs::kRefitAfterFit ? std::string("short re-fit of what the fit left, iterations")
                                                  : "re-fit round " + std::to_string(round) + ", iterations");
        }
        refit_iteration = status.iteration;
        refit->update(status.iteration, status.iterations);
    };
    const jobs::PruneResult result = jobs::prune_scene(renderer, cloud, cameras, options, progress);
    chunks.print(context);
    if (result.sanitize.changed())
        std::fprintf(stderr, "sanitised %s: %s\n", args.scene.c_str(), result.sanitize.summary().c_str());
    if (!result.lossless_applied)
        std::fprintf(stderr, "note: %s holds scores without pixel counts: no lossless pass\n", args.load_scores.c_str());
    print_result(result, args.out);
    return 0;
}

}  // namespace

void register_prune(CLI::App& app, Action& action) {
    auto* command = app.add_subcommand("prune", "drop the Gaussians a scene's pictures need least");
    command->footer(
        "Selection (one of; default --max-psnr-drop 0.1): --threshold drops score <= T, --ratio drops the\n"
        "lowest fraction R, --keep keeps the best N, --max-psnr-drop finds the smallest model whose mean\n"
        "PSNR on the test views drops at most D dB, --max-mb keeps the model of least PSNR drop whose file\n"
        "(in the output's format) fits in M megabytes, trading Gaussians against SH bands dropped per\n"
        "Gaussian. Every method first drops the Gaussians that touch no pixel of the training views\n"
        "(lossless on those views).\n"
        "Example:\n  vksplat prune lego/point_cloud.ply --cameras lego/cameras.json --method blend \\\n"
        "      --ratio 0.5 --images lego/images --background 1,1,1 -o lego_half.ply\n"
        "  (add --recover to re-fit what is kept to the photos, --recover-seconds 60 to give it a minute:\n"
        "   see vksplat finetune)");
    auto args = std::make_shared<PruneArgs>();
    command->add_option("scene", args->scene, "scene file (any format vksplat reads)")->required()->check(CLI::ExistingFile);
    command->add_option("--cameras", args->cameras, "cameras.json, transforms.json or a COLMAP sparse folder")
        ->required()
        ->check(CLI::ExistingPath);
    command->add_option("--method", args->method,
                        "importance score (default: blend, or blend-mix with --recover: the best measured for each)")
        ->check(CLI::IsMember(prune::score_method_names()));
    auto* threshold =
        command->add_option("--threshold", args->threshold, "drop Gaussians whose score is <= T")->check(number_in());
    auto* ratio = command->add_option("--ratio", args->ratio, "drop this fraction of the Gaussians (0..1)")
                      ->check(number_in(0.0, 1.0));
    auto* keep = command->add_option("--keep", args->keep, "keep this many Gaussians")->check(count_in(0));
    auto* budget = command->add_option("--max-psnr-drop", args->max_psnr_drop,
                                       "smallest model losing at most D dB of mean PSNR on the test views")
                       ->check(number_in(0.0));
    auto* max_mb = command->add_option("--max-mb", args->max_mb,
                                       "best model whose output file fits in M megabytes (10^6 bytes), SH bands\n"
                                       "dropped per Gaussian where the format stores zeros compactly (.spz)")
                       ->check(positive_number());
    threshold->excludes(ratio, keep, budget, max_mb);
    ratio->excludes(keep, budget, max_mb);
    keep->excludes(budget, max_mb);
    budget->excludes(max_mb);
    command
        ->add_flag("--allow-sh-reduction", args->allow_sh_reduction,
                   "with the PSNR budget, also try fewer SH bands at the count found")
        ->excludes(threshold, ratio, keep, max_mb);
    command->add_option("--images", args->images, "photos to measure quality against (else the unpruned render)")
        ->check(CLI::ExistingDirectory);
    command->add_option("--test-views", args->test_views,
                        "held-out views, e.g. 0-12 (default: the cameras' test split, else the first 13 if there are more, else all)");
    command->add_option("--train-views", args->train_views, "views to score on (default: all but the test views)");
    command->add_option("--background", args->background, "background colour R,G,B in [0,1]")
        ->delimiter(',')
        ->expected(3)
        ->check(number_in(0.0, 1.0));
    command->add_option("--sh-degree", args->sh_degree, "write the scene with at most this SH degree")
        ->check(count_in(0, 3));
    command->add_option("--sh-bits", args->sh_bits,
                        "B1,B2: keep B1 bits of SPZ's SH byte for degree 1 and B2 for degrees 2 and 3 (1..8; "
                        "SPZ's own encoder: 5,4); a smaller SPZ, and --max-mb measures at it")
        ->delimiter(',')
        ->expected(2);  // the range is the library's to refuse (prune::check_sh_precision), as for convert
    command->add_option("--save-scores", args->save_scores, "write the scores as float32 [N] .npy");
    command->add_option("--save-totals", args->save_totals, "write the view totals as float32 [N, 5] .npy");
    command->add_option("--load-scores", args->load_scores, "scores or totals saved before, instead of rendering")
        ->check(CLI::ExistingFile);
    command->add_option("--seed", args->seed,
                        "seed of the random method, and with --recover of the training views' order and the\n"
                        "rounds' samples")
        ->check(count_in(0));
    // "auto" is what a bare --recover reads: CLI11 checks the value it stands for like a given one.
    auto* recover = command->add_option("--recover", args->recover,
                        "re-fit the kept Gaussians to the photos (needs --images) for N iterations, without N\n"
                        "for 5,000 up to half dropped, rising to 50,000 at 80% and 60,000 at 90%; with\n"
                        "--max-psnr-drop every probe is re-fitted, so the budget holds after re-fitting;\n"
                        "with --max-mb the count chosen is reached in the rounds (--rounds), its SH bands\n"
                        "are dropped again, and the file still fits")
        ->expected(0, 1)
        ->default_str("auto")
        ->check(CLI::IsMember({"auto"}) | count_in(1))
        ->type_name("[N]");
    auto* recover_seconds = command->add_option("--recover-seconds", args->recover_seconds,
                        "re-fit (as --recover does) for S seconds of wall time in all, shared by the rounds,\n"
                        "instead of a count of iterations (with --max-psnr-drop: each probe's re-fit)");
    auto* rounds = command->add_option("--rounds", args->rounds,
                                       "with --recover: prune and re-fit in R rounds (default 5, or one per 1,000\n"
                                       "iterations where fewer; with --max-psnr-drop 1, the only choice), each dropping a geometrically growing share, ranked on the\n"
                                       "re-fitted model and kept as a weighted sample by score; every round but the\n"
                                       "last re-fits 1,000 iterations, the last the rest")
                       ->check(count_in(1, 100));
    auto* round_spacing = command->add_option("--round-spacing", args->round_spacing,
                                              "with --recover: iterations of every round but the last (default 1000;\n"
                                              "0: the rounds share the iterations or seconds equally)")
                              ->check(count_in(0));
    auto* round_keep = command->add_option("--round-keep", args->round_keep,
                                           "with --recover: each round keeps a weighted random sample by score\n"
                                           "(sample, the default) or the best-scored (best)")
                           ->check(CLI::IsMember({"sample", "best"}));
    auto* position_lr = command->add_option("--position-lr", args->position_lr,
                                            "with --recover: decay (default) the position rate from its initial to\n"
                                            "its final value in each re-fit, or keep it at the final value")
                            ->check(CLI::IsMember({"final", "decay"}));
    const auto sums = add_gradient_sums_flags(*command, args->sums, "with --recover: ");
    CLI::Option* deterministic = sums.first;
    CLI::Option* fast_sums = sums.second;
    command->add_option("-o,--out", args->out, "pruned scene (.ply, .compressed.ply, .splat or .spz)")->required();
    command->add_flag("--force", args->force, "overwrite existing output files");
    add_gpu_options(*command, args->gpu);
    command->callback([&action, args, recover, recover_seconds, rounds, round_spacing, round_keep, position_lr,
                       deterministic, fast_sums] {
        for (const CLI::Option* option : {rounds, round_spacing, round_keep, position_lr, deterministic, fast_sums})
            if (option->count() && !recover->count() && !recover_seconds->count())
                throw CLI::RequiresError(option->get_name(), "--recover or --recover-seconds");
        action = [args] { return run_prune(*args); };
    });
}

}  // namespace vksplat::cli
