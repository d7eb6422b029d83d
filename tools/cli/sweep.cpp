// vksplat sweep: every pruning method at a list of dropped fractions, measured and charted.
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "cluster_options.hpp"
#include "commands.hpp"
#include "number_checks.hpp"
#include "progress.hpp"
#include "vksplat/io/cameras.hpp"
#include "vksplat/sweep/sweep.hpp"
#include "vksplat/jobs/view_selection.hpp"

namespace vksplat::cli {
namespace {

struct SweepArgs {
    GpuOptions gpu;
    std::string scene, cameras, images, out, test_views, train_views;
    std::vector<std::string> methods;
    std::vector<double> fractions, sheet_fractions{0.5, 0.8, 0.9};
    size_t max_train_views = 0, timing_views = 3;
    int timing_reps = 5, timing_warmup = 1;
    bool no_scoring_cost = false;
    std::vector<float> background{0, 0, 0};
    uint64_t seed = 0;
    bool force = false;
    uint64_t recover = 0;
    std::optional<int> recover_rounds;
    std::vector<std::string> sizes = sweep::SweepOptions().size_formats;
    ClusterStageArgs cluster;  // the cluster method's stages 1-6
};

void print_row(const sweep::SweepRow& row) {
    std::printf("%-12s drop %-5s  %9zu Gaussians %8.2f MB  PSNR %7.3f (%+.3f) dB  SSIM %.4f  vs unpruned %6.2f dB  "
                "%8.2f ms\n",
                row.method.c_str(), sweep::fraction_label(row.fraction).c_str(),
                row.measure.gaussians, double(row.measure.bytes) / 1e6, row.measure.psnr, row.delta_psnr,
                row.measure.ssim, row.measure.psnr_vs_unpruned, row.measure.ms_per_frame);
    std::fflush(stdout);  // one line per row as it happens, also when stdout is a pipe
}

int run_sweep(const SweepArgs& args) {
    std::vector<std::string> warnings;
    const GaussianCloud cloud = read_scene_file(args.scene);
    const auto cameras = io::read_cameras(args.cameras, &warnings);
    for (const auto& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());

    sweep::SweepOptions options;
    // No --methods: the default per-Gaussian methods (sweep::default_methods) and cluster pruning.
    if (args.methods.empty()) {
        options.methods = sweep::default_methods();
        options.cluster = true;
    }
    for (const auto& name : args.methods) {
        if (name == sweep::kClusterMethod)
            options.cluster = true;
        else
            options.methods.push_back(prune::parse_score_method(name));
    }
    if (options.cluster) {
        ClusterStageArgs cluster = args.cluster;
        resolve_cluster_stage_args(cluster, cameras.size());
        options.cluster_options = cluster.options;
    }
    options.fractions = args.fractions;
    if (!args.test_views.empty()) options.test_views = jobs::parse_view_list(args.test_views, cameras.size());
    if (!args.train_views.empty()) options.train_views = jobs::parse_view_list(args.train_views, cameras.size());
    options.max_train_views = args.max_train_views;
    options.images_dir = args.images;
    options.settings.background = {args.background[0], args.background[1], args.background[2]};
    options.seed = args.seed;
    options.timing_views = args.timing_views;
    options.timing_warmup = args.timing_warmup;
    options.timing_repetitions = args.timing_reps;
    options.compare_scoring_cost = !args.no_scoring_cost;
    options.sheet_fractions = args.sheet_fractions;
    options.recover_iterations = args.recover;
    options.recover_rounds = args.recover_rounds;
    options.size_formats = args.sizes;
    options.scene_label = args.scene;
    options.out_dir = args.out;
    options.mode = args.force ? io::WriteMode::overwrite : io::WriteMode::refuse_existing;

    gpu::Context context(args.gpu.context_options());
    Renderer renderer(context);
    std::fprintf(stderr, "sweeping %zu Gaussians on %s\n", cloud.size(), context.info().name.c_str());
    if (context.info().type == VK_PHYSICAL_DEVICE_TYPE_CPU)
        std::fprintf(stderr, "note: %s is a CPU device: its frame times say little about a GPU's\n",
                     context.info().name.c_str());
    // One progress line per stage, started when the stage first reports.
    std::unique_ptr<ProgressLine> line;
    std::string stage;
    sweep::SweepProgress progress;
    ChunkReport chunks;
    progress.step = [&](const std::string& name, size_t done, size_t total, std::optional<double> seconds_left) {
        chunks.saw(renderer.last_frame().chunks);
        if (name != stage || !line) line = std::make_unique<ProgressLine>(name), stage = name;
        line->update(done, total, seconds_left);
    };
    progress.row = print_row;
    const sweep::SweepResult result = sweep::sweep_scene(renderer, cloud, cameras, options, progress);
    chunks.print(context);

    std::printf("unpruned: PSNR %.3f dB, SSIM %.4f, %.2f ms per frame, %.2f MB\n", result.unpruned.psnr,
                result.unpruned.ssim, result.unpruned.ms_per_frame, double(result.unpruned.bytes) / 1e6);
    std::printf("scoring %zu training views: %.1f s", result.train_views.size(), result.scoring_seconds);
    if (result.plain_render_seconds > 0)
        std::printf(" (plain rendering: %.1f s, ratio %.2f)", result.plain_render_seconds,
                    result.scoring_seconds / result.plain_render_seconds);
    std::printf("\nbest method: %s\n%s\nwrote %s\nwrote %s\n", result.best_method.c_str(),
                sweep::summary_line(result).c_str(), result.csv.c_str(), result.report.c_str());
    return 0;
}

}  // namespace

void register_sweep(CLI::App& app, Action& action) {
    auto* command = app.add_subcommand("sweep", "compare the pruning methods at many dropped fractions");
    command->footer(
        "Writes sweep.csv, sh_degrees.csv, totals.npy, charts/*.svg, sheets/*.png and report.html into the\n"
        "output folder.\n"
        "Example:\n  vksplat sweep lego/point_cloud.ply --cameras lego/cameras.json --images lego/images \\\n"
        "      --background 1,1,1 --out sweep_lego\n"
        "A quick run: --methods blend,random --fractions 0,0.5,0.9 --max-train-views 10 --timing-reps 0\n"
        "The cluster method renders and segments up to 50 of the training views first (see vksplat cluster);\n"
        "the options of its stages are those of vksplat cluster, with the same defaults.");
    auto args = std::make_shared<SweepArgs>();
    command->add_option("scene", args->scene, "scene file (any format vksplat reads)")->required()->check(CLI::ExistingFile);
    command->add_option("--cameras", args->cameras, "cameras.json, transforms.json or a COLMAP sparse folder")
        ->required()
        ->check(CLI::ExistingPath);
    command->add_option("--images", args->images, "the photos of the test views")
        ->required()
        ->check(CLI::ExistingDirectory);
    command->add_option("-o,--out", args->out, "folder for the results")->required();
    std::vector<std::string> method_names = prune::score_method_names();
    method_names.push_back(sweep::kClusterMethod);
    command->add_option("--methods", args->methods,
                        "methods to sweep (default: all); cluster is cluster pruning at its default settings, "
                        "ranked at the same kept counts")
        ->delimiter(',')
        ->check(CLI::IsMember(method_names));
    command->add_option("--fractions", args->fractions, "dropped fractions (default: 0,0.1,...,0.9,0.95,0.98)")
        ->delimiter(',')
        ->check(number_in(0.0, 1.0));
    command->add_option("--test-views", args->test_views,
                        "held-out views, e.g. 0-12 (default: the cameras' test split, else the first 13 if there are more, else all)");
    command->add_option("--train-views", args->train_views, "views to score on (default: all but the test views)");
    command->add_option("--max-train-views", args->max_train_views,
                        "score on at most N training views, evenly spaced (default: all)")
        ->check(count_in(0));
    command->add_option("--timing-views", args->timing_views, "test views to time (0: all)")
        ->capture_default_str()
        ->check(count_in(0));
    command->add_option("--timing-reps", args->timing_reps,
                        "timed frames per view (0: time each test view's one measuring render instead)")
        ->check(count_in(0, 1000000))
        ->capture_default_str();
    command->add_option("--timing-warmup", args->timing_warmup, "untimed frames per view first")
        ->check(count_in(0, 1000000))
        ->capture_default_str();
    command->add_flag("--no-scoring-cost", args->no_scoring_cost,
                      "skip rendering the training views plainly to compare with scoring");
    command->add_option("--sheet-fractions", args->sheet_fractions,
                        "comparison sheets of the best method at these of the swept fractions")
        ->delimiter(',')
        ->check(number_in(0.0, 1.0))
        ->capture_default_str();
    command->add_option("--background", args->background, "background colour R,G,B in [0,1]")
        ->delimiter(',')
        ->expected(3)
        ->check(number_in(0.0, 1.0));
    command->add_option("--seed", args->seed, "seed of the random method")->check(count_in(0));
    command->add_option("--recover", args->recover,
                        "also re-fit every pruned model to the photos for N iterations (prune --recover's schedule) "
                        "and add it as method <name>+recover; needs --images")
        ->check(count_in(0));
    command->add_option("--recover-rounds", args->recover_rounds, "prune-re-fit rounds of each --recover point")
        ->capture_default_str()
        ->check(count_in(1, 20));
    command->add_option("--sizes", args->sizes,
                        "scene formats every model is written in to chart PSNR against its size in each (add sog\n"
                        "for SOG: its k-means takes about 27 s per 40,000 Gaussians on two CPU cores)")
        ->delimiter(',')
        ->capture_default_str();
    command->add_flag("--force", args->force, "overwrite the results of an earlier sweep in the folder");
    auto* cluster = command->add_option_group("cluster method", "with --methods ...,cluster: its stages' options "
                                                                 "(vksplat cluster; the same defaults)");
    add_cluster_stage_options(*cluster, args->cluster, kRegions | kProject | kBuild | kScore);
    add_gpu_options(*command, args->gpu);
    command->callback([&action, args] { action = [args] { return run_sweep(*args); }; });
}

}  // namespace vksplat::cli
