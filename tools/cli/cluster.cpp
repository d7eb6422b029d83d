// vksplat cluster: saliency-aware cluster pruning, one subcommand per stage plus `run` for all.
// Each stage reads what the stages before it saved in --work (see jobs/cluster_work_dir.hpp).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include "cluster_options.hpp"
#include "commands.hpp"
#include "number_checks.hpp"
#include "progress.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/cameras.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/jobs/cluster_work_dir.hpp"
#include "vksplat/jobs/finetune.hpp"
#include "vksplat/jobs/prune_scene.hpp"
#include "vksplat/jobs/subject_quality.hpp"
#include "vksplat/jobs/view_selection.hpp"

namespace vksplat::cli {
namespace {

struct ClusterArgs {
    GpuOptions gpu;
    std::string scene, cameras, work, out, import_dir, images, test_views;
    std::string subject = "auto", subject_masks, sheets;
    std::string ratio_of = "gaussians";
    std::string preset = "auto";
    bool preset_given = false, score_or_selection_given = false;  // on the command line
    std::vector<float> background{0, 0, 0};
    std::optional<double> score_threshold, max_psnr_drop;
    std::string recover;  // --recover's N, "auto" without one (by the fraction dropped), empty if not given
    std::optional<double> recover_seconds;
    std::string recover_loss = "subject";
    bool force = false;
    ClusterStageArgs stage;  // the options of stages 1-6
};

void add_common(CLI::App& c, ClusterArgs& a) {
    c.add_option("scene", a.scene, "scene file (any format vksplat reads)")->required()->check(CLI::ExistingFile);
    c.add_option("--cameras", a.cameras, "cameras.json, transforms.json or a COLMAP sparse folder")
        ->required()
        ->check(CLI::ExistingPath);
    c.add_option("--work", a.work, "folder for the stages' outputs")->required();
    c.add_option("--background", a.background, "background colour R,G,B in [0,1]")
        ->delimiter(',')
        ->expected(3)
        ->check(number_in(0.0, 1.0));
    c.add_flag("--force", a.force, "overwrite existing outputs");
}

void add_prune(CLI::App& c, ClusterArgs& a) {
    auto* threshold =
        c.add_option("--score-threshold", a.score_threshold, "drop clusters whose G* is below this")->check(number_in());
    auto& rule = a.stage.options.selection;
    auto* ratio = c.add_option("--prune-ratio", rule.ratio, "else drop this fraction (see --ratio-of), lowest G* first")
        ->check(number_in(0.0, 1.0))
        ->capture_default_str()
        ->excludes(threshold);
    c.add_option("--ratio-of", a.ratio_of, "what --prune-ratio counts: gaussians, or clusters (the original rule)")
        ->check(CLI::IsMember({"gaussians", "clusters"}))
        ->capture_default_str();
    auto* contribution = c.add_option("--max-contribution-loss", rule.max_contribution_loss,
                                      "stop before the dropped clusters paint more than this share of the picture (1: no limit)")
                             ->check(number_in(0.0, 1.0))
                             ->capture_default_str();
    c.add_option("--max-psnr-drop", a.max_psnr_drop,
                 "instead: the fewest Gaussians, clusters whole from the best G* down, whose mean PSNR on the test "
                 "views drops at most D dB (against --images, else the unpruned render)")
        ->check(number_in(0.0))
        ->excludes(threshold)
        ->excludes(ratio)
        ->excludes(contribution);
    c.add_option("-o,--out", a.out, "pruned scene (.ply, .compressed.ply, .splat or .spz)")->required();
    c.add_option("--images", a.images, "photos: measure the test views against them too")->check(CLI::ExistingDirectory);
    c.add_option("--test-views", a.test_views, "views to measure on (default: the cameras' test split, else the first 13)");
    auto* subject = c.add_option("--subject", a.subject,
                                 "the subject region the test views are also scored in: auto (the ball around the "
                                 "cameras' common focus, radius 0.3 x their median distance to it) or x,y,z,r")
                        ->capture_default_str();
    c.add_option("--subject-masks", a.subject_masks,
                 "instead: a folder of subject mask images named like the photos (white = subject)")
        ->check(CLI::ExistingDirectory)
        ->excludes(subject);
    c.add_option("--sheets", a.sheets,
                 "with --images: a comparison sheet per test view here (photo | unpruned | pruned | subject region | "
                 "error heat map)")
        ->needs(c.get_option("--images"));
    auto* recover = c.add_option("--recover", a.recover,
                                 "then re-fit what is kept on the training views' photos (--images), in one round, "
                                 "for N iterations (without N: by the fraction dropped, as prune --recover)")
                        ->expected(0, 1)
                        ->default_str("auto")  // what a bare --recover reads, checked like a given value
                        ->check(CLI::IsMember({"auto"}) | count_in(1))
                        ->type_name("[N]");
    auto* recover_seconds = c.add_option("--recover-seconds", a.recover_seconds,
                                         "re-fit (as --recover does) for S seconds of wall time instead of N iterations");
    recover->excludes(c.get_option("--max-psnr-drop"));
    recover_seconds->excludes(c.get_option("--max-psnr-drop"));
    auto* loss = c.add_option("--recover-loss", a.recover_loss,
                              "with --recover: what the loss looks at, the subject region of each view (background "
                              "pixels ignored) or the whole picture")
                     ->check(CLI::IsMember({"subject", "picture"}))
                     ->capture_default_str();
    c.parse_complete_callback([=] {
        if (loss->count() && !recover->count() && !recover_seconds->count())
            throw CLI::RequiresError("--recover-loss", "--recover or --recover-seconds");
    });
}

bool refits(const ClusterArgs& args) { return !args.recover.empty() || args.recover_seconds; }

void log_line(const std::string& line) {
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
}

void print_scores(const char* what, const jobs::SubjectScores& s) {
    std::printf("  %-22s PSNR %7.3f dB  SSIM %.4f   subject PSNR %7.3f dB  SSIM %.4f\n", what, s.psnr, s.ssim,
                s.subject_psnr, s.subject_ssim);
}

int run_stages(ClusterArgs& args, unsigned stages) {
    const io::WriteMode mode = args.force ? io::WriteMode::overwrite : io::WriteMode::refuse_existing;
    // The pruned scene's name must say a format we write before the stages before it run.
    if (stages & kPrune) io::check_scene_writable(args.out, mode);
    std::vector<std::string> warnings;
    GaussianCloud cloud = read_scene_file(args.scene);
    const SanitizeReport report = sanitize(cloud);
    if (report.changed()) std::fprintf(stderr, "sanitised %s: %s\n", args.scene.c_str(), report.summary().c_str());
    const auto cameras = io::read_cameras(args.cameras, &warnings);
    for (const auto& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());

    args.stage.options.settings.background = {args.background[0], args.background[1], args.background[2]};
    resolve_cluster_stage_args(args.stage, cameras.size());
    auto& options = args.stage.options;
    options.selection.threshold = args.score_threshold;
    options.selection.ratio_of = cluster::parse_ratio_of(args.ratio_of);
    if (args.preset != "auto") {
        jobs::apply_cluster_preset(jobs::parse_cluster_preset(args.preset), options);
    } else if (stages & (kScore | kPrune) && (args.preset_given || !args.score_or_selection_given)) {
        // Explicit score or selection options win over the automatic choice; --preset auto does not
        // mix with them (CLI11 refuses both).
        const jobs::ClusterPresetChoice choice = jobs::choose_cluster_preset(cloud, cameras, options);
        jobs::apply_cluster_preset(choice.preset, options);
        log_line(jobs::describe(choice));
    }
    jobs::ClusterStageIo io{args.work, mode, log_line, {}};
    std::filesystem::create_directories(args.work);

    std::unique_ptr<gpu::Context> context;
    std::unique_ptr<Renderer> renderer;
    if (stages & (kRegions | kProject) || (stages & kPrune && (!args.images.empty() || args.max_psnr_drop || refits(args)))) {
        context = std::make_unique<gpu::Context>(args.gpu.context_options());
        renderer = std::make_unique<Renderer>(*context);
    }
    const auto timed = [](const char* stage, auto&& work) {
        const auto start = std::chrono::steady_clock::now();
        work();
        std::printf("[%s] %.1f s\n", stage,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        std::fflush(stdout);
    };
    if (stages & kRegions)
        timed("regions", [&] {
            ProgressLine line("region maps");
            io.progress = [&](size_t done, size_t total) { line.update(done, total); };
            std::optional<std::filesystem::path> import;
            if (!args.import_dir.empty()) import = args.import_dir;
            jobs::regions_stage(*renderer, cloud, cameras, options, import, io);
        });
    if (stages & kProject)
        timed("project", [&] {
            ProgressLine line("projected views");
            io.progress = [&](size_t done, size_t total) { line.update(done, total); };
            jobs::project_stage(*renderer, *context, cloud, cameras, options, io);
        });
    if (stages & kBuild) timed("build", [&] { jobs::build_stage(cloud, options, io); });
    if (stages & kScore) timed("score", [&] { jobs::score_stage(cloud, cameras, options, io); });
    if (stages & kPrune) {
        const auto views = args.test_views.empty() ? jobs::default_test_views(cameras)
                                                   : jobs::parse_view_list(args.test_views, cameras.size());
        std::vector<Camera> test;
        for (size_t v : views) test.push_back(cameras[v]);
        if (refits(args) && args.images.empty()) throw InputError("--recover", "needs the photos: give --images");
        std::string region;
        const jobs::SubjectMasks masks =
            args.images.empty() ? jobs::SubjectMasks{}
                                : jobs::subject_masks(jobs::parse_subject_spec(args.subject, args.subject_masks), cameras, &region);
        jobs::ClusterPruneResult result;
        timed("prune", [&] {
            if (refits(args)) {
                jobs::RecoverOptions recover;
                if (!args.recover.empty() && args.recover != "auto") recover.iterations = std::stoull(args.recover);
                recover.seconds = args.recover_seconds;
                recover.finetune.train.background = options.settings.background;
                ProgressLine line("re-fit iterations");
                const auto done = jobs::recover_stage(
                    *context, *renderer, cloud, cameras, options,
                    jobs::photos_in_folder(args.images, options.settings.background), recover,
                    args.recover_loss == "subject" ? masks : jobs::SubjectMasks{}, args.out, io,
                    [&](const train::LoopStatus& s) { line.update(s.iteration, s.iterations); });
                result = done.prune;
                const auto& refit = done.recover.rounds.back().refit;
                std::printf("re-fitted %llu iterations in %.1f s (%s loss, %zu views)\n",
                            static_cast<unsigned long long>(refit.iterations), refit.seconds,
                            done.masked_views ? "subject-masked" : "whole-picture", refit.train_views.size());
                return;
            }
            if (!args.max_psnr_drop) {
                result = jobs::prune_stage(cloud, options, args.out, io);
                return;
            }
            const eval::TestViews targets =
                args.images.empty() ? eval::render_targets(*renderer, cloud, test, options.settings)
                                    : eval::photo_targets(test, args.images, options.settings.background);
            const prune::QualityBudget budget{.max_psnr_drop = *args.max_psnr_drop};
            result = jobs::prune_stage_to_budget(*renderer, cloud, targets, budget, options.settings, args.out, io,
                                                 [](const prune::BudgetProbe& p) {
                                                     std::printf("  probe: keep %zu, PSNR %.3f dB, drop %.3f dB%s (%.1f s)\n",
                                                                 p.kept, p.psnr, p.drop, p.meets ? "" : " - over",
                                                                 p.seconds);
                                                     std::fflush(stdout);
                                                 });
        });
        std::printf("clusters: %zu, dropped %zu", result.clusters, result.clusters_dropped);
        // The budget measures its drop on the test views (printed below), not in painted share.
        if (!result.budget)
            std::printf(", painting %.2f%% of the picture%s", 100.0 * result.contribution_dropped,
                        result.stopped_by_contribution ? " (stopped by --max-contribution-loss before the ratio)" : "");
        std::printf("\nGaussians: %zu -> %zu (%.1f%% kept)\nsize: %zu bytes as PLY -> %zu bytes written\nwrote %s\n",
                    result.count_before, result.count_after,
                    result.count_before ? 100.0 * double(result.count_after) / double(result.count_before) : 0.0,
                    result.bytes_before, result.bytes_after, args.out.c_str());
        if (result.count_after == 0) std::printf("warning: the pruned scene is empty\n");
        if (result.budget)
            std::printf("quality budget %.3f dB: kept %zu, drop %.3f dB (%zu probes)\n", *args.max_psnr_drop,
                        result.budget->kept, result.budget->drop, result.budget->probes.size());
        if (!args.images.empty()) {
            const GaussianCloud pruned = io::read_scene(args.out);  // as written: what the user gets
            std::optional<jobs::SubjectSheets> sheets;
            if (!args.sheets.empty()) sheets = jobs::SubjectSheets{.dir = args.sheets, .mode = io.mode};
            const auto q =
                jobs::measure_subject_quality(*renderer, cloud, pruned, test, args.images, options.settings, masks, sheets);
            std::printf("test views (%zu), subject region (%s) %.1f%% of the pixels", test.size(), region.c_str(),
                        100 * q.subject_fraction);
            if (q.views_without_subject) std::printf(", none in %zu views", q.views_without_subject);
            std::printf(":\n");
            print_scores("unpruned vs photos", *q.unpruned_vs_photos);
            print_scores("pruned vs photos", *q.pruned_vs_photos);
            print_scores("pruned vs unpruned", q.pruned_vs_unpruned);
        }
    }
    return 0;
}

CLI::App* add_stage(CLI::App& cluster, Action& action, const char* name, const char* help, unsigned stages,
                    const char* example) {
    auto* command = cluster.add_subcommand(name, help);
    command->footer(std::string("Example:\n  ") + example);
    auto args = std::make_shared<ClusterArgs>();
    add_common(*command, *args);
    add_cluster_stage_options(*command, args->stage, stages);
    if (stages & kRegions)
        command->add_option("--import", args->import_dir,
                          "use region maps made elsewhere: view_NNNN or <image stem> .npy (int32 [H,W] or uint8 masks "
                          "[K,H,W]) or .png (16-bit labels, 0 = none)")
            ->check(CLI::ExistingDirectory);
    if (stages & kPrune) add_prune(*command, *args);
    CLI::Option* preset = nullptr;
    std::vector<CLI::Option*> score_and_selection;
    if (stages & (kScore | kPrune)) {
        preset = command->add_option(
            "--preset", args->preset,
            "named score and selection settings: auto (keep-subject where at least half of the Gaussians are room "
            "the views do not look at, else whole-picture; the default unless a score or selection option is "
            "given), keep-subject (drop the room: lambda 1, 80% of the Gaussians, no limit on the picture's loss), "
            "whole-picture (the defaults: half the Gaussians while the dropped paint at most 0.2% of the picture) or "
            "original (the issue's G*, 90% of the clusters); excludes the options it sets");
        preset->check(CLI::IsMember({"auto", "whole-picture", "keep-subject", "original"}))->capture_default_str();
        for (const char* name : {"--alpha", "--beta", "--gamma", "--mvr-mean-frac-weight", "--kappa", "--lambda",
                                 "--central-threshold", "--prune-ratio", "--ratio-of", "--max-contribution-loss",
                                 "--score-threshold"})
            if (CLI::Option* option = command->get_option_no_throw(name)) {
                preset->excludes(option);
                score_and_selection.push_back(option);
            }
        // A quality budget is a selection too: the automatic choice leaves it the whole-picture ranking.
        if (CLI::Option* budget = command->get_option_no_throw("--max-psnr-drop")) score_and_selection.push_back(budget);
    }
    if (stages & (kRegions | kProject) || stages & kPrune) add_gpu_options(*command, args->gpu);
    command->callback([&action, args, stages, preset, score_and_selection] {
        args->preset_given = preset && preset->count() > 0;
        args->score_or_selection_given = std::any_of(score_and_selection.begin(), score_and_selection.end(),
                                                     [](const CLI::Option* option) { return option->count() > 0; });
        action = [args, stages] { return run_stages(*args, stages); };
    });
    return command;
}

}  // namespace

void register_cluster(CLI::App& app, Action& action) {
    auto* cluster = app.add_subcommand("cluster", "saliency-aware cluster pruning, stage by stage or all at once");
    cluster->require_subcommand(1);
    cluster->footer(
        "Stages: regions (render and segment views) -> project (view filter, region id per Gaussian) -> build\n"
        "(neighbours + union-find) -> score (G* per cluster) -> prune (write the scene). Each reads the\n"
        "outputs the earlier ones left in --work, so a stage can be re-run with new parameters alone.\n"
        "G* = -alpha*spatial - beta*depth + gamma*MVR + kappa*contribution (the largest share of the picture a\n"
        "member paints) + lambda*[central] (the views look at it: centrality >= --central-threshold).\n"
        "Defaults: contribution alone (kappa 1); drop the lowest clusters until half the Gaussians are gone\n"
        "or the dropped ones would paint more than --max-contribution-loss of the picture. The issue's method:\n"
        "--alpha 0.1 --beta 0.1 --gamma 1 --kappa 0 --prune-ratio 0.9 --ratio-of clusters --max-contribution-loss 1\n"
        "To keep the subject and drop the room: --preset keep-subject (--lambda 1 --prune-ratio 0.8\n"
        "--max-contribution-loss 1); --preset original for the issue's method.\n"
        "Without a preset or a score or selection option, score and prune choose (--preset auto): keep-subject\n"
        "where at least half of the Gaussians are room (centrality under --central-threshold in the rendered\n"
        "views: the views do not look at them), else whole-picture; they print the choice and its numbers.\n"
        "Example:\n  vksplat cluster run snowmiku/point_cloud.ply --cameras snowmiku/cameras.json --work w -o out.ply");
    const unsigned all = kRegions | kProject | kBuild | kScore | kPrune;
    add_stage(*cluster, action, "regions", "render training views and segment them into region maps", kRegions,
              "vksplat cluster regions scene.ply --cameras cameras.json --work w --max-views 30");
    add_stage(*cluster, action, "project", "filter the views, then find each Gaussian's region in each", kProject,
              "vksplat cluster project scene.ply --cameras cameras.json --work w --occlusion blend");
    add_stage(*cluster, action, "build", "cluster neighbouring Gaussians whose regions agree", kBuild,
              "vksplat cluster build scene.ply --cameras cameras.json --work w --delta-dist auto");
    add_stage(*cluster, action, "score", "score every cluster (G*) and print the percentiles", kScore,
              "vksplat cluster score scene.ply --cameras cameras.json --work w --alpha 0.2");
    add_stage(*cluster, action, "prune", "drop the clusters of lowest G* and write the scene", kPrune,
              "vksplat cluster prune scene.ply --cameras cameras.json --work w --prune-ratio 0.5 -o out.ply");
    add_stage(*cluster, action, "run", "all stages", all,
              "vksplat cluster run scene.ply --cameras cameras.json --work w --delta-dist auto -o out.ply");
}

}  // namespace vksplat::cli
