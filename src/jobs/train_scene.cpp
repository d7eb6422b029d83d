// The training job: data in, the reference recipe's loop, outputs written.
#include "vksplat/jobs/train_scene.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <numeric>
#include <random>

#include <nlohmann/json.hpp>

#include "jobs/fingerprint.hpp"
#include "vksplat/io/output_folders.hpp"
#include "jobs/run_checkpoint.hpp"
#include "jobs/training_report.hpp"
#include "jobs/training_setup.hpp"
#include "vksplat/camera/camera_focus.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/dataset.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/io/sfm_points.hpp"
#include "vksplat/jobs/view_selection.hpp"
#include "vksplat/train/initialize.hpp"
#include "stats/median.hpp"
#include "vksplat/prune/accumulate.hpp"
#include "vksplat/prune/scores.hpp"
#include "vksplat/prune/selection.hpp"

namespace vksplat::jobs {
namespace {

namespace fs = std::filesystem;
// What training holds per Gaussian besides its SH: 11 raw parameters, 3 copies (parameters and
// Adam's two moments: Adam steps inside the backward pass, so there is no gradient array; the
// preprocess reads them raw, so there is no activated copy either); per-splat gradient sums 72
// (64-bit fixed point; 36 as floats), the SH backward's inputs 32, densification sums 12, and the
// frame's per-Gaussian arrays (about 100 bytes) with some tile entries (8 bytes each for keys and
// values, twice for the sort's ping-pong, ~6 per Gaussian). Densification holds no more: it frees
// the frame's and the per-splat arrays while it gathers one array at a time.
constexpr uint64_t kParameterCopies = 3;
constexpr uint64_t kFixedBytesPerGaussian = kParameterCopies * 11 * 4 + 72 + 32 + 12 + 100 + 6 * 16;
// Per pixel: the frame's colour, depth and count, the trainer's transmittance, last position,
// pixel gradient and photo, and the loss's nine planes.
constexpr uint64_t kBytesPerPixel = 24 + 28 + 36;

// The history records the count after every this many steps.
constexpr uint64_t kSnapshotEvery = 500;

// The box random starting points fill for INRIA cameras without points: centred where the cameras
// look together, as wide as the median camera sees at its distance from there (what the
// photos can show). For lego this is the reference's +-1.3 box within 10%. Without a common
// focus (parallel axes), the box around the cameras' mean as large as their spread.
io::SfmPoints points_around_cameras(const std::vector<Camera>& cameras, size_t count, uint64_t seed) {
    glm::dvec3 centre(0.0);
    double half = 0;
    if (const auto focus = common_focus(cameras)) {
        std::vector<double> seen;
        for (const auto& c : cameras)
            seen.push_back(glm::length(c.centre() - *focus) * 0.5 * c.width / c.fx);
        centre = *focus;
        half = stats::median(std::move(seen));
    } else {
        for (const auto& c : cameras) centre += c.centre();
        centre /= double(cameras.size());
        for (const auto& c : cameras) half = std::max(half, glm::length(c.centre() - centre));
    }
    io::SfmPoints points = train::random_points(count, -float(half), float(half), seed);
    for (size_t i = 0; i < points.size(); ++i)
        for (int k = 0; k < 3; ++k) points.positions[3 * i + k] += float(centre[k]);
    return points;
}

DensifyStrategy chosen_strategy(const TrainRecipe& recipe) {
    if (recipe.strategy != DensifyStrategy::automatic) return recipe.strategy;
    return recipe.densify.max_gaussians > 0 ? DensifyStrategy::budget : DensifyStrategy::lean;
}

// A seeded random `count` of the cloud's Gaussians, in their order.
GaussianCloud random_subset(const GaussianCloud& cloud, size_t count, uint64_t seed) {
    std::vector<size_t> order(cloud.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::mt19937_64 rng(seed ^ 0x5bd1e995u);
    std::shuffle(order.begin(), order.end(), rng);
    std::vector<uint8_t> keep(cloud.size(), 0);
    for (size_t k = 0; k < count; ++k) keep[order[k]] = 1;
    return cloud.subset(keep);
}

// Median GPU time of each pass of a step, in recording order.
nlohmann::json stages_json(const std::vector<StageTiming>& stages) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& stage : stages) out.push_back({{"stage", stage.stage}, {"ms", stage.milliseconds}});
    return out;
}

nlohmann::json history_json(const std::vector<TrainSnapshot>& history) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& h : history)
        out.push_back({{"iteration", h.iteration},
                       {"gaussians", h.gaussians},
                       {"test_psnr", h.test_psnr ? nlohmann::json(*h.test_psnr) : nlohmann::json()}});
    return out;
}

void write_json(const fs::path& path, const nlohmann::json& json, io::WriteMode mode) {
    io::write_file_atomically(path, mode, [&](std::ostream& out) { out << json.dump(2) << '\n'; });
}

// The recipe's settings as a checkpoint records them ("reference" for the reference recipe).
std::string recipe_text(const TrainRecipe& r) {
    if (chosen_strategy(r) == DensifyStrategy::reference) return "reference";
    if (chosen_strategy(r) == DensifyStrategy::lean)
        return "lean: until " + std::to_string(r.lean.densify_until) + ", keeping " + std::to_string(r.lean.keep_share) +
               " of the blend weight in " + std::to_string(r.budget.settle.rounds) + " x " +
               std::to_string(r.budget.settle.spacing) + (r.budget.settle.restart_decay ? " restarting the decay" : "");
    if (chosen_strategy(r) == DensifyStrategy::mcmc) {
        const auto& m = r.mcmc;
        return "mcmc: every " + std::to_string(m.refine_every) + " from " + std::to_string(m.refine_from) + " until " +
               std::to_string(m.refine_until) + ", growth " + std::to_string(m.growth) + ", opacity " +
               std::to_string(m.min_opacity) + ", regularisers " + std::to_string(m.opacity_regularization) + " " +
               std::to_string(m.scale_regularization) + ", noise " + std::to_string(m.position_noise) + ", start " +
               std::to_string(m.start_opacity) + " " + std::to_string(m.start_scale) + " " +
               std::to_string(r.start_fraction);
    }
    const auto& b = r.budget;
    return "budget: growth " + std::to_string(b.growth_exponent) + " to " + std::to_string(b.reach) + ", ranking " +
           std::to_string(int(b.ranking)) + ", gradient " + std::to_string(b.min_gradient) + ", prune " +
           std::to_string(b.prune_ratio) + ", peak " + std::to_string(b.peak) + " to at most " +
           std::to_string(b.peak_limit) + " until " + std::to_string(b.densify_until) +
           ", settling " + std::to_string(b.settle.rounds) + " x " + std::to_string(b.settle.spacing) +
           (b.settle.restart_decay ? " restarting the decay" : "") + (b.reset_opacity ? ", opacity resets" : "") +
           (b.prune_large ? ", large pruned" : "") +
           (r.budget_sampling ? ", sampling" : "") +
           ", scored by " + std::string(prune::to_string(r.budget_score)) + ", start " +
           std::to_string(r.start_fraction);
}

// What a training run's checkpoint belongs to: the starting Gaussians, the cameras (at the
// resolution trained) and the recipe; --iters may change.
train::CheckpointOwner training_owner(const TrainingData& data, const TrainOptions& options) {
    const auto& r = options.recipe;
    return {"training from " + data.folder.string(),
            {{"starting Gaussians", fingerprint(data.initial)},
             {"cameras", fingerprint(data.cameras)},
             {"training views", list_text(data.train_views)},
             {"background", colour_text(options.background)},
             {"seed", std::to_string(options.seed)},
             {"densification", "until " + std::to_string(r.densify_until) + ", threshold " +
                                   std::to_string(r.densify.grad_threshold) + ", at most " +
                                   std::to_string(r.densify.max_gaussians) + ", " + recipe_text(r)},
             {"SH degree", std::to_string(r.sh_degree)}}};
}

}  // namespace

std::string_view to_string(DensifyStrategy strategy) {
    switch (strategy) {
        case DensifyStrategy::automatic: return "automatic";
        case DensifyStrategy::reference: return "reference";
        case DensifyStrategy::lean: return "lean";
        case DensifyStrategy::budget: return "budget";
        case DensifyStrategy::mcmc: return "mcmc";
    }
    return "?";
}

DensifyStrategy parse_densify_strategy(std::string_view name) {
    for (auto s : {DensifyStrategy::automatic, DensifyStrategy::reference, DensifyStrategy::lean, DensifyStrategy::budget,
                   DensifyStrategy::mcmc})
        if (name == to_string(s)) return s;
    throw InputError("--strategy " + std::string(name), "unknown; choose automatic, reference, lean, budget or mcmc");
}

size_t gaussians_within(uint64_t budget, int sh_degree, uint64_t pixels) {
    const uint64_t per_gaussian =
        kFixedBytesPerGaussian + kParameterCopies * 4 * uint64_t(sh_coefficients_for_degree(sh_degree)) * 3;
    const uint64_t per_image = pixels * kBytesPerPixel;
    return budget > per_image ? static_cast<size_t>((budget - per_image) / per_gaussian) : 0;
}

TrainingData load_training_data(const fs::path& data_dir, const TrainRecipe& recipe, double resolution_scale,
                                uint64_t seed) {
    if (!(resolution_scale > 0 && resolution_scale <= 1))
        throw InputError("--resolution-scale " + std::to_string(resolution_scale), "must lie in (0, 1]");
    io::Dataset dataset = io::read_dataset(data_dir, recipe.test_every);
    if (!fs::is_directory(dataset.images_dir))
        throw InputError(dataset.images_dir.string(), "no such folder of photos");
    TrainingData data;
    data.format = dataset.format;
    data.cameras = std::move(dataset.cameras);
    data.images_dir = dataset.images_dir;
    data.inputs = std::move(dataset.files);
    data.warnings = std::move(dataset.warnings);
    data.notices = std::move(dataset.notices);
    data.undistortion = std::move(dataset.undistortion);
    data.folder = data_dir;
    // Where the data names no split (an INRIA file without "split"), INRIA's convention: the first
    // 13 cameras are held out, and a dozen cameras or fewer are all test and all training views.
    // A split naming every camera a test view leaves nothing to train on.
    if (std::all_of(data.cameras.begin(), data.cameras.end(), [](const Camera& c) { return c.split == "test"; }))
        throw InputError(data_dir.string(), "every camera is a test view (\"split\"): nothing is left to train on");
    data.test_views = default_test_views(data.cameras);
    data.train_views = default_train_views(data.cameras.size(), data.test_views);
    if (data.train_views.empty()) throw InputError(data_dir.string(), "has no training views");
    data.held_out = views_held_out(data.test_views, data.train_views);

    // What training starts from: the SfM points where the data has them; else random points, in
    // the NeRF-synthetic box or in the box the cameras see around their common focus.
    const io::SfmPoints points =
        dataset.points                     ? std::move(*dataset.points)
        : data.format == "nerf-synthetic" ? train::random_points(recipe.random_points, -recipe.random_box,
                                                                  recipe.random_box, seed)
                                           : points_around_cameras(data.cameras, recipe.random_points, seed);
    if (resolution_scale != 1.0)
        for (auto& camera : data.cameras)
            camera = camera.resized(std::max(1, int(std::lround(camera.width * resolution_scale))),
                                    std::max(1, int(std::lround(camera.height * resolution_scale))));
    data.initial = train::initial_cloud(points, recipe.sh_degree);
    return data;
}

train::Importance settling_importance(const gpu::Context& context, const TrainingData& data, const TrainOptions& options) {
    RenderSettings settings;
    settings.background = options.background;
    const bool sampling = options.recipe.budget_sampling;
    const prune::ScoreMethod method = options.recipe.budget_score;
    return [&context, settings, &data, sampling, method, seed = options.seed](const GaussianCloud& cloud) {
        // A renderer of its own each time, so that its device memory is held only while it scores.
        Renderer renderer(context);
        // Blend weights depend on each Gaussian's shape and opacity, never on its colour, so the
        // scene is rendered without its higher SH bands (three quarters of its bytes at degree 3,
        // held beside the trainer's scene): the same statistics. The Fisher score's loss sees colour.
        const bool colour = prune::needs_fisher(method);
        const prune::ViewTotals totals = prune::accumulate(renderer, colour ? cloud : cloud.with_sh_degree(0),
                                                           data.cameras, data.train_views, settings, {}, colour);
        std::vector<float> scores = prune::score(cloud, totals, method, seed);
        // Seeded by the count too, which differs between rounds and is the same in a resumed run.
        return sampling ? prune::sampling_keys(prune::sampling_weights(scores, method), seed ^ (uint64_t(cloud.size()) << 20))
                        : scores;
    };
}

TrainResult train_scene(const gpu::Context& context, const TrainingData& data, const PhotoSource& photos,
                        const TrainOptions& options, const TestMeasure& measure,
                        const std::function<void(const train::LoopStatus&)>& progress) {
    const TrainRecipe& recipe = options.recipe;
    const DensifyStrategy strategy_kind = chosen_strategy(recipe);
    if (strategy_kind == DensifyStrategy::lean && !(recipe.lean.keep_share > 0 && recipe.lean.keep_share <= 1))
        throw InputError("--keep-share " + std::to_string(recipe.lean.keep_share), "must lie in (0, 1]");
    if ((strategy_kind == DensifyStrategy::budget || strategy_kind == DensifyStrategy::mcmc) &&
        recipe.densify.max_gaussians == 0)
        throw InputError("--strategy " + std::string(to_string(strategy_kind)),
                         "needs --max-gaussians: the budget it trains to");
    TrainResult result;
    result.ply = fs::absolute(options.out_dir / "point_cloud.ply");
    result.cameras_json = fs::absolute(options.out_dir / "cameras.json");
    result.metrics_json = fs::absolute(options.out_dir / "metrics.json");
    result.report = fs::absolute(options.out_dir / "report.html");
    const fs::path checkpoint = options.out_dir / "checkpoint";
    const auto notice = [&](const std::string& line) {
        if (options.notice) options.notice(line);
    };
    // Every output checked before anything slow: none may be an input (-o DATA would replace its
    // cameras.json), none is replaced unless asked for or resuming, the folder must take files.
    std::vector<fs::path> outputs = {result.ply, result.cameras_json, result.metrics_json};
    for (const auto& path : training_report_files(options.out_dir)) outputs.push_back(fs::absolute(path));
    for (const auto& path : outputs) io::refuse_input_as_output(path, data.inputs);
    io::OutputFolders folders;  // removed again if the run is refused before it writes
    folders.create(options.out_dir);
    for (const auto& path : outputs) io::check_writable(path, options.resume ? io::WriteMode::overwrite : options.mode);
    train::TrainOptions train_options;
    train_options.checkpoint_owner = training_owner(data, options);
    const auto resumed = check_run_checkpoint({checkpoint, data.inputs, outputs}, train_options.checkpoint_owner,
                                              options.resume, options.mode);
    if (!data.held_out) notice(kTestViewsTrainedOnWarning);

    const std::map<size_t, train::Photo> train_photos = training_photos(photos, data.cameras, data.train_views);
    uint64_t largest_image = 0;
    for (size_t view : data.train_views)
        largest_image = std::max<uint64_t>(largest_image, uint64_t(data.cameras[view].width) * data.cameras[view].height);
    eval::TestViews test;
    test.photos = true;
    for (size_t view : data.test_views) {
        test.cameras.push_back(data.cameras[view]);
        test.targets.push_back(checked_photo(photos, data.cameras[view]).rgb);
    }

    // The memory budget caps growth; a start beyond it is refused.
    const uint64_t budget = options.memory_budget > 0 ? options.memory_budget : context.memory_budget();
    const size_t room = gaussians_within(budget, recipe.sh_degree, largest_image);
    if (data.initial.size() > room)
        throw InputError("--memory-budget", "holds about " + std::to_string(room) + " Gaussians at this resolution, "
                                            "fewer than the " + std::to_string(data.initial.size()) +
                                            " training starts from; raise it or lower --resolution-scale");
    train::ReferenceSchedule schedule = recipe;
    if (strategy_kind == DensifyStrategy::budget) schedule.densify_until = recipe.budget.densify_until;
    if (strategy_kind == DensifyStrategy::lean) schedule.densify_until = recipe.lean.densify_until;
    if (recipe.densify.max_gaussians > room)
        notice("--max-gaussians " + std::to_string(recipe.densify.max_gaussians) + ": the memory budget holds about " +
               std::to_string(room) + " Gaussians at this resolution; training to " + std::to_string(room));
    schedule.densify.max_gaussians = schedule.densify.max_gaussians > 0 ? std::min(schedule.densify.max_gaussians, room) : room;
    schedule.white_background = options.background == std::array<float, 3>{1.0f, 1.0f, 1.0f};
    result.strategy = std::string(to_string(strategy_kind));
    std::optional<GaussianCloud> subset;  // of the starting points, where the budget asks for fewer
    std::unique_ptr<train::Strategy> strategy;
    train::BudgetStrategy* budget_strategy = nullptr;
    train::ReferenceStrategy* reference_strategy = nullptr;
    train::McmcStrategy* mcmc_strategy = nullptr;
    train::SettleSchedule settle = recipe.budget.settle;
    settle.at = std::min(schedule.densify_until, recipe.iterations);
    settle.iterations = recipe.iterations;
    const size_t budget_count = schedule.densify.max_gaussians;
    if (strategy_kind == DensifyStrategy::budget || strategy_kind == DensifyStrategy::mcmc) {
        const size_t most = std::max<size_t>(1, size_t(std::llround(double(budget_count) * recipe.start_fraction)));
        if (data.initial.size() > most) {
            subset = random_subset(data.initial, most, options.seed);
            notice("budget " + std::to_string(budget_count) + ": starting from a random " + std::to_string(most) +
                   " of the " + std::to_string(data.initial.size()) + " starting points, so that growth has room");
        }
    }
    if (strategy_kind == DensifyStrategy::reference || strategy_kind == DensifyStrategy::lean) {
        // A run that ends within the lean window densifies throughout, as the reference does:
        // settling at its last step would leave nothing to re-fit what it keeps. Without a window
        // (--densify-until 0) nothing grew that settling should take back.
        std::optional<train::Settling> settling;
        if (strategy_kind == DensifyStrategy::lean && settle.at > 0 && settle.at < recipe.iterations)
            settling.emplace(settle, train::SettleTarget{.share = recipe.lean.keep_share},
                             settling_importance(context, data, options));
        strategy = std::make_unique<train::ReferenceStrategy>(schedule, std::move(settling));
        reference_strategy = static_cast<train::ReferenceStrategy*>(strategy.get());
    } else if (strategy_kind == DensifyStrategy::mcmc) {
        train::McmcSchedule mcmc = recipe.mcmc;
        mcmc.budget = budget_count;
        if (!subset) subset = data.initial;
        // The paper starts every Gaussian at opacity 0.5: relocation draws by opacity, and the
        // reference's 0.1 would leave the first draws to chance.
        const float logit = float(std::log(mcmc.start_opacity / (1.0 - mcmc.start_opacity)));
        std::fill(subset->opacity_logits.begin(), subset->opacity_logits.end(), logit);
        for (float& s : subset->log_scales) s += float(std::log(mcmc.start_scale));
        strategy = std::make_unique<train::McmcStrategy>(schedule, mcmc);
        mcmc_strategy = static_cast<train::McmcStrategy*>(strategy.get());
        train::use_mcmc_terms(mcmc, train_options);
    } else {
        train::BudgetSchedule budget = recipe.budget;
        budget.budget = budget_count;
        budget.start = subset ? subset->size() : data.initial.size();
        budget.settle = settle;
        // The peak fits in memory too.
        budget.peak = std::max(1.0, std::min(budget.peak, double(room) / double(budget.budget)));
        const size_t peak = train::peak_count(budget);
        std::string growth = "budget " + std::to_string(budget.budget) + ": growing to " + std::to_string(peak) + " Gaussians";
        if (peak > budget.budget)
            growth += ", then keeping the " + std::to_string(budget.budget) + " of most blend weight from step " +
                      std::to_string(settle.at) + " on";
        train::BudgetSchedule unlimited = budget;
        unlimited.ask_peak(budget.peak);
        if (train::peak_count(unlimited) > peak)
            growth += " (growth beyond the budget stops at " + std::to_string(budget.peak_limit) +
                      " Gaussians; --budget-peak lifts the limit)";
        notice(growth);
        strategy = std::make_unique<train::BudgetStrategy>(schedule, budget, settling_importance(context, data, options));
        budget_strategy = static_cast<train::BudgetStrategy*>(strategy.get());
    }

    result.scene_extent = training_extent(data.cameras, data.train_views, notice);
    if (resumed) notice(resume_notice(*resumed, recipe.iterations));
    train_options.scene_extent = result.scene_extent;
    train_options.background = options.background;
    train_options.deterministic = options.deterministic;
    train_options.blend_backward = options.blend_backward;
    train_options.position_schedule = train::PositionSchedule::decay;
    train_options.rates = recipe.rates;
    train_options.rates.position_decay_steps = int(std::min<uint64_t>(recipe.iterations, 1u << 30));
    std::unique_ptr<train::Trainer> trainer =
        options.resume ? std::make_unique<train::Trainer>(context, checkpoint, train_options)
                       : std::make_unique<train::Trainer>(context, subset ? *subset : data.initial, train_options);

    train::LoopOptions loop{.iterations = recipe.iterations,
                            .seed = options.seed,
                            .checkpoint = checkpoint,
                            .checkpoint_every = options.checkpoint_every,
                            .stop = options.stop,
                            .source = "training from " + data.folder.string(),
                            .snapshot_every = kSnapshotEvery,
                            .snapshot = [&](train::Trainer& t, uint64_t iteration) {
                                TrainSnapshot snapshot{iteration, t.size(), {}};
                                const bool last = iteration == recipe.iterations;
                                if (measure && !test.cameras.empty() && options.evaluate_every > 0 &&
                                    (iteration % options.evaluate_every == 0 || last)) {
                                    t.release_frame();  // the measure renders with a frame of its own
                                    snapshot.test_psnr = measure(t.cloud(), test).mean_psnr;
                                }
                                result.history.push_back(snapshot);
                            }};
    static_cast<train::LoopResult&>(result) =
        train::run_training_loop(*trainer, *strategy, data.cameras, data.train_views, train_photos, loop, progress);
    result.evaluate_seconds = result.snapshot_seconds;
    if (train_options.blend_backward == train::BlendBackward::fastest &&
        trainer->blend_backward() != train::BlendBackward::fastest)
        notice(std::string("blend backward: ") +
               (trainer->blend_backward() == train::BlendBackward::per_splat ? "per splat" : "per pixel") +
               ", the faster of its two forms on this device");
    if (budget_strategy) result.importance_prunes = budget_strategy->events();
    if (reference_strategy) result.importance_prunes = reference_strategy->events();
    if (mcmc_strategy) result.mcmc_events = mcmc_strategy->events();
    result.gaussians = trainer->size();
    if (result.interrupted) return result;
    const GaussianCloud trained = trainer->cloud();
    trainer.reset();  // its device memory goes before the test renders
    if (!test.cameras.empty() && measure) result.test = measure(trained, test);

    const auto mode = io::WriteMode::overwrite;  // checked above: asked for, resuming, or new
    io::write_scene(trained, result.ply, mode, "ply");
    // Each camera's split as this run used it, so that the folder re-reads with the same split.
    std::vector<Camera> cameras = data.cameras;
    for (size_t view : data.train_views) cameras[view].split = "train";
    for (size_t view : data.test_views) cameras[view].split = "test";
    io::write_inria_cameras(result.cameras_json, cameras, mode);
    // No held-out views (COLMAP with --test-every 0, NeRF without transforms_test.json): no test
    // quality, null rather than a PSNR of 0.
    const auto measured = [&](double value) {
        return result.test.psnr.empty() ? nlohmann::json() : nlohmann::json(value);
    };
    nlohmann::json metrics{{"data_format", data.format},
                           {"iterations", result.iterations},
                           {"skipped_steps", result.skipped},
                           {"gaussians", result.gaussians},
                           {"seconds", result.seconds},
                           {"densify_seconds", result.strategy_seconds},
                           {"scene_change_seconds",
                            {{"wait", result.scene_changes.wait},
                             {"read_back", result.scene_changes.read_back},
                             {"plan", result.scene_changes.plan},
                             {"relayout", result.scene_changes.relayout},
                             {"frame_allocation", result.scene_changes.frame_allocation}}},
                           {"gpu_ms_per_iteration", result.gpu_ms_per_iteration},
                           {"peak_device_bytes", result.peak_device_bytes},
                           {"scene_extent", result.scene_extent},
                           {"train_views", data.train_views.size()},
                           {"test_views", data.test_views.size()},
                           {"test_psnr", measured(result.test.mean_psnr)},
                           {"test_ssim", measured(result.test.mean_ssim)},
                           {"test_psnr_per_view", result.test.psnr},
                           {"strategy", result.strategy},
                           {"deterministic", options.deterministic},
                           {"pruned_by_importance", result.importance_prunes.pruned},
                           {"importance_seconds", result.importance_prunes.importance_seconds},
                           {"relocated", result.mcmc_events.relocated},
                           {"added_by_relocation", result.mcmc_events.added},
                           {"evaluate_seconds", result.evaluate_seconds},
                           {"history", history_json(result.history)},
                           {"gpu_ms_per_stage", stages_json(result.stages)}};
    write_json(result.metrics_json, metrics, mode);
    write_training_report(options.out_dir, result, data.folder.string(), mode);
    return result;
}

}  // namespace vksplat::jobs
