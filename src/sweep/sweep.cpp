// The sweep job: sanitise, gather the view totals once, then per method one ranking cut at every
// fraction and measured (cluster pruning's ranking from its own stages); the unpruned scene at each
// SH degree; sheets of the best method; files.
#include "vksplat/sweep/sweep.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string>

#include "vksplat/io/output_folders.hpp"
#include "sweep_parts.hpp"
#include "vksplat/error.hpp"
#include "vksplat/eval/metrics.hpp"
#include "vksplat/jobs/prune_recover.hpp"
#include "vksplat/jobs/prune_scene.hpp"
#include "vksplat/jobs/render_views.hpp"
#include "vksplat/prune/accumulate.hpp"
#include "vksplat/eval/quality.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/prune/score_files.hpp"
#include "vksplat/prune/selection.hpp"

namespace vksplat::sweep {

std::vector<prune::ScoreMethod> default_methods() {
    std::vector<prune::ScoreMethod> methods;
    for (const std::string& name : prune::score_method_names()) {
        const prune::ScoreMethod method = prune::parse_score_method(name);
        if (!prune::needs_fisher(method)) methods.push_back(method);
    }
    return methods;
}

namespace {

namespace fs = std::filesystem;
using detail::Targets;
using detail::Work;

using detail::Reporter;
using detail::kept_count;

// What the sweep writes into out_dir; any of them there already means an earlier sweep's results.
const char* const kOutputFiles[] = {"sweep.csv", "sh_degrees.csv", "totals.npy", "report.html"};
const char* const kOutputFolders[] = {"charts", "sheets"};

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void check_options(const SweepOptions& options, size_t camera_count) {
    if (options.out_dir.empty()) throw InputError("sweep", "no output folder given");
    if (fs::exists(options.out_dir) && !fs::is_directory(options.out_dir))
        throw InputError(options.out_dir.string(), "is not a folder");
    if (options.images_dir.empty()) throw InputError("sweep", "no photos given: the sweep measures against them");
    if (!fs::is_directory(options.images_dir))
        throw InputError(options.images_dir.string(), "is not a folder of photos");
    for (double f : options.fractions)
        if (!(f >= 0 && f <= 1))
            throw InputError("fraction " + std::to_string(f), "must lie in [0, 1] (the fraction to drop)");
    if (options.timing_repetitions < 0) throw InputError("timing repetitions", "must be 0 or more");
    if (options.timing_warmup < 0) throw InputError("timing warm-up", "must be 0 or more");
    if (!(options.sheet_max_error > 0)) throw InputError("sheet max error", "must be positive");
    for (const std::string& format : options.size_formats) {
        try {
            io::check_scene_writable(fs::temp_directory_path() / "vksplat-size", io::WriteMode::overwrite, format);
        } catch (const InputError&) {
            throw InputError("size format '" + format + "'", "is not one vksplat writes (ply, compressed-ply, splat, "
                                                             "spz, spz-v4, sog, gltf)");
        }
    }
    for (const auto* views : {&options.test_views, &options.train_views})
        for (size_t view : *views)
            if (view >= camera_count)
                throw InputError("view " + std::to_string(view),
                                 "there are only " + std::to_string(camera_count) + " cameras");
}

// The outputs in out_dir (which exists): none there from an earlier sweep unless overwriting,
// and the folder writable.
void check_outputs(const SweepOptions& options) {
    for (const char* name : kOutputFiles) io::check_writable(options.out_dir / name, options.mode);
    if (options.mode == io::WriteMode::refuse_existing)
        for (const char* name : kOutputFolders)
            if (fs::exists(options.out_dir / name))
                throw InputError((options.out_dir / name).string(),
                                 "already exists (results of an earlier sweep?); not overwritten (--force replaces "
                                 "them)");
}

std::vector<prune::ScoreMethod> methods_of(const SweepOptions& options) {
    if (!options.methods.empty() || options.cluster) return options.methods;
    return default_methods();
}

Targets make_targets(Renderer& renderer, const GaussianCloud& cloud, const std::vector<Camera>& cameras,
                     const SweepOptions& options) {
    Targets targets;
    targets.cameras = cameras;
    targets.photos = eval::photo_targets(cameras, options.images_dir, options.settings.background).targets;
    targets.unpruned = eval::render_targets(renderer, cloud, cameras, options.settings).targets;
    return targets;
}

// The unpruned scene rendered at each SH degree up to its own, against the photos.
std::vector<ShDegreeMeasure> measure_sh_degrees(Renderer& renderer, const GaussianCloud& cloud, const Targets& targets,
                                                const SweepOptions& options, Reporter& reporter) {
    std::vector<ShDegreeMeasure> degrees;
    renderer.set_scene(cloud);
    for (int degree = 0; degree <= cloud.sh_degree; ++degree) {
        reporter.step("SH degrees", size_t(degree), size_t(cloud.sh_degree) + 1);
        reporter.clock.begin(Work::render);
        RenderSettings settings = options.settings;
        settings.max_sh_degree = degree;
        ShDegreeMeasure m;
        m.degree = degree;
        m.bytes = cloud.with_sh_degree(degree).ply_bytes();
        for (size_t v = 0; v < targets.cameras.size(); ++v) {
            const RenderOutput image = renderer.render(targets.cameras[v], settings);
            m.view_psnr.push_back(eval::psnr(image.rgb.data(), targets.photos[v].data(), image.width, image.height));
            m.psnr += m.view_psnr.back();
            m.ssim += eval::ssim(image.rgb.data(), targets.photos[v].data(), image.width, image.height);
            reporter.clock.advance(1);
        }
        m.psnr /= double(targets.cameras.size());
        m.ssim /= double(targets.cameras.size());
        degrees.push_back(std::move(m));
    }
    reporter.step("SH degrees", size_t(cloud.sh_degree) + 1, size_t(cloud.sh_degree) + 1);
    return degrees;
}

// What rendering the training views costs without statistics: the yardstick for scoring.
double plain_render_seconds(Renderer& renderer, const GaussianCloud& cloud, const std::vector<Camera>& cameras,
                            const std::vector<size_t>& views, const RenderSettings& settings,
                            Reporter& reporter) {
    renderer.set_scene(cloud);
    double seconds = 0;
    reporter.clock.begin(Work::plain_view);
    for (size_t i = 0; i < views.size(); ++i) {
        reporter.step("plain renders of the training views", i, views.size());
        const auto start = std::chrono::steady_clock::now();
        renderer.render(cameras[views[i]], settings);
        seconds += seconds_since(start);
        reporter.clock.advance(1);
    }
    reporter.step("plain renders of the training views", views.size(), views.size());
    return seconds;
}

std::vector<double> swept_sheet_fractions(const SweepOptions& options, const std::vector<double>& fractions) {
    std::vector<double> chosen;
    for (double f : options.sheet_fractions)
        if (std::any_of(fractions.begin(), fractions.end(), [&](double g) { return std::abs(f - g) < 1e-9; }))
            chosen.push_back(f);
    return chosen;
}

// prune --recover's schedule on the sweep's views; each row sets the ranking method.
jobs::RecoverOptions recover_schedule(const SweepResult& result, const SweepOptions& options) {
    jobs::RecoverOptions recover;
    recover.iterations = options.recover_iterations;
    recover.rounds = options.recover_rounds;
    recover.finetune.train_views = result.train_views;
    recover.finetune.test_views = result.test_views;
    recover.finetune.train.background = options.settings.background;
    recover.finetune.train.sh_degree = options.settings.max_sh_degree;
    return recover;
}

// The row of `pruned` (cut at `keep` from the ranking of `scores`) re-fitted with prune --recover's
// schedule, which ranks the same scores its own way (jobs::recover_ranking).
SweepRow recover_row(Renderer& renderer, const GaussianCloud& cloud, std::span<const float> scores,
                     std::span<const uint8_t> candidates, size_t keep,
                     const std::string& method, const SweepRow& pruned, const std::vector<Camera>& cameras,
                     const jobs::PhotoSource& photos, const Targets& targets, const SweepResult& result,
                     const SweepOptions& options, Reporter& reporter) {
    jobs::RecoverOptions recover = recover_schedule(result, options);
    // Cluster scores rank whole clusters: the first round cuts them whole, as cluster pruning does;
    // its later rounds rank by the re-fit's default (recover_schedule's).
    if (method != kClusterMethod) recover.method = prune::parse_score_method(method);
    if (method == kClusterMethod) recover.sampled = false;
    // One stage per re-fit, its iterations counted over all its rounds.
    const std::string stage = "re-fit of " + method + " at " + fraction_label(pruned.fraction) + " dropped";
    const uint64_t iterations = options.recover_iterations;
    uint64_t reported = 0;
    const int rounds = jobs::recover_rounds(recover, iterations);
    const auto refit_progress = [&](int round, const train::LoopStatus& status) {
        uint64_t done = status.iteration;
        for (int r = 1; r < round; ++r) done += jobs::round_iterations(iterations, r, rounds, recover.round_spacing);
        reporter.clock.advance(double(done - std::min(done, reported)));
        reported = std::max(reported, done);
        reporter.step(stage, size_t(reported), size_t(iterations));
    };
    reporter.step(stage, 0, size_t(iterations));
    reporter.clock.begin(Work::refit_iteration);
    const auto start = std::chrono::steady_clock::now();
    const jobs::RecoverResult refit =
        jobs::prune_and_recover(renderer.context(), renderer, cloud, scores, candidates,
                                std::min(keep, prune::count_kept(candidates)),
                                cameras, photos, recover, {}, refit_progress);
    SweepRow row = pruned;
    row.method = method + kRecoverSuffix;
    row.recover_seconds = seconds_since(start);
    row.recover_iterations = iterations;
    reporter.clock.advance(double(iterations - std::min(iterations, reported)));  // steps the loop did not report
    reporter.clock.begin(Work::measure);
    row.measure = detail::measure_model(renderer, refit.cloud, targets, options);
    reporter.clock.advance(1);
    row.delta_psnr = row.measure.psnr - result.unpruned.psnr;
    return row;
}

// The views cluster pruning renders regions of (at most max_views of them, 0: all).
size_t cluster_region_views(const jobs::ClusterOptions& cluster) {
    return cluster.max_views == 0 ? cluster.views.size() : std::min(cluster.views.size(), cluster.max_views);
}

// The sweep's work, for the time left: every render, model measured, training view scored, re-fit
// iteration and sheet it will do. Cluster pruning's region views count as scoring views (each is a
// render and a segmentation), until its own time is known.
void plan_work(detail::WorkClock& clock, const GaussianCloud& cloud, size_t rankings,
               const std::vector<double>& fractions, const SweepResult& result, const SweepOptions& options) {
    const double test_views = double(result.test_views.size()), train_views = double(result.train_views.size());
    const size_t refits =
        options.recover_iterations > 0
            ? rankings * size_t(std::count_if(fractions.begin(), fractions.end(), [](double f) { return f > 0; }))
            : 0;
    clock.plan(Work::render, test_views * double(cloud.sh_degree + 2));  // targets, then each SH degree
    clock.plan(Work::measure, double(1 + rankings * fractions.size() + refits));
    clock.plan(Work::scoring_view, train_views);
    if (options.cluster) {
        jobs::ClusterOptions cluster = options.cluster_options;
        if (cluster.views.empty()) cluster.views = result.train_views;
        clock.plan(Work::scoring_view, double(cluster_region_views(cluster)));
    }
    if (options.compare_scoring_cost) clock.plan(Work::plain_view, train_views);
    clock.plan(Work::refit_iteration, double(refits * options.recover_iterations));
    clock.plan(Work::sheet, double(swept_sheet_fractions(options, fractions).size()) * test_views);
}

}  // namespace

std::string fraction_label(double fraction) {
    char text[48];
    std::snprintf(text, sizeof(text), "%.4f", fraction);
    std::string label = text;
    while (label.back() == '0') label.pop_back();
    if (label.back() == '.') label.pop_back();
    return label;
}

std::vector<double> default_sweep_fractions() { return {0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 0.98}; }

std::vector<size_t> spread_views(const std::vector<size_t>& views, size_t count) {
    if (count == 0 || count >= views.size()) return views;
    std::vector<size_t> picked;
    for (size_t i = 0; i < count; ++i) picked.push_back(views[i * views.size() / count]);
    return picked;
}

std::string best_method(const std::vector<SweepRow>& rows) {
    if (rows.empty()) throw std::invalid_argument("sweep::best_method: no rows");
    std::vector<std::string> order;
    std::map<std::string, std::pair<double, size_t>> sums;
    for (const SweepRow& row : rows) {
        if (row.method.ends_with(kRecoverSuffix)) continue;
        if (std::find(order.begin(), order.end(), row.method) == order.end()) order.push_back(row.method);
        if (row.fraction <= 0) continue;
        sums[row.method].first += row.measure.psnr;
        ++sums[row.method].second;
    }
    std::string best = order.front();
    double best_mean = -std::numeric_limits<double>::infinity();
    for (const std::string& method : order) {
        const auto it = sums.find(method);
        if (it == sums.end()) continue;
        const double mean = it->second.first / double(it->second.second);
        if (mean > best_mean) best_mean = mean, best = method;
    }
    return best;
}

SweepResult sweep_scene(Renderer& renderer, const GaussianCloud& input, const std::vector<Camera>& cameras,
                        const SweepOptions& options, const SweepProgress& progress) {
    check_options(options, cameras.size());
    const std::vector<prune::ScoreMethod> methods = methods_of(options);
    const std::vector<double> fractions = options.fractions.empty() ? default_sweep_fractions() : options.fractions;

    SweepResult result;
    result.device = renderer.context().info().name;
    result.device_is_cpu = renderer.context().info().type == VK_PHYSICAL_DEVICE_TYPE_CPU;
    jobs::ViewSplit split = jobs::split_views(cameras, options.test_views, options.train_views);
    result.test_views = std::move(split.test);
    result.train_views = spread_views(split.train, options.max_train_views);
    std::vector<Camera> test_cameras;
    std::vector<std::string> stems;
    const std::vector<std::string> camera_stems = jobs::output_stems(cameras);
    for (size_t view : result.test_views) {
        test_cameras.push_back(cameras[view]);
        stems.push_back(camera_stems[view]);
        result.test_view_names.push_back(cameras[view].name.empty() ? stems.back() : cameras[view].name);
    }
    // Made first, for check_outputs; removed again unless something is written into it.
    io::OutputFolders folders;
    folders.create(options.out_dir);
    check_outputs(options);

    // Sanitised once here, so that totals, scores and masks all index the same Gaussians.
    GaussianCloud cloud = input;
    result.sanitize = sanitize(cloud);
    // Photos first, the re-fits' too: a missing one is reported before the long part.
    std::optional<jobs::PhotoSource> photos;
    if (options.recover_iterations > 0) {
        photos = jobs::photos_in_folder(options.images_dir, options.settings.background);
        jobs::check_recover(recover_schedule(result, options), cameras, *photos);
    }
    Reporter reporter{progress, {}};
    plan_work(reporter.clock, cloud, methods.size() + (options.cluster ? 1 : 0), fractions, result, options);
    const char* const unpruned_stage = "photos and the unpruned scene";
    reporter.step(unpruned_stage, 0, 2);
    reporter.clock.begin(Work::render);
    const Targets targets = make_targets(renderer, cloud, test_cameras, options);
    reporter.clock.advance(double(test_cameras.size()));
    reporter.step(unpruned_stage, 1, 2);
    reporter.clock.begin(Work::measure);
    result.unpruned = detail::measure_model(renderer, cloud, targets, options);
    reporter.clock.advance(1);
    reporter.step(unpruned_stage, 2, 2);
    result.sh_degrees = measure_sh_degrees(renderer, cloud, targets, options, reporter);

    const auto scoring_start = std::chrono::steady_clock::now();
    reporter.clock.begin(Work::scoring_view);
    size_t scored = 0;
    const prune::ViewTotals totals = prune::accumulate(
        renderer, cloud, cameras, result.train_views, options.settings, [&](size_t done, size_t total) {
            reporter.clock.advance(double(done - std::min(done, scored)));
            scored = std::max(scored, done);
            reporter.step("scoring the training views", done, total);
        },
        std::ranges::any_of(methods, prune::needs_fisher));
    result.scoring_seconds = seconds_since(scoring_start);
    if (options.compare_scoring_cost)
        result.plain_render_seconds =
            plain_render_seconds(renderer, cloud, cameras, result.train_views, options.settings, reporter);
    const prune::KeepMask candidates = prune::lossless_mask(totals);
    result.lossless_dropped = cloud.size() - prune::count_kept(candidates);

    // Every fraction the lossless pass alone covers keeps the same model, whatever the method.
    std::optional<ModelMeasure> lossless_only;
    const size_t total_rows = (methods.size() + (options.cluster ? 1 : 0)) * fractions.size();
    const auto sweep_ranking = [&](const std::string& method, const std::vector<float>& scores) {
        const prune::Ranking ranking(scores, candidates);
        std::vector<SweepRow> recovered;
        for (double fraction : fractions) {
            reporter.step("sweep", result.rows.size(), total_rows);
            const size_t keep = kept_count(cloud.size(), fraction);
            SweepRow row;
            row.method = method;
            row.fraction = fraction;
            reporter.clock.begin(Work::measure);
            if (keep >= ranking.candidates()) {
                if (lossless_only) {
                    reporter.clock.plan(Work::measure, -1);  // measured once already
                } else {
                    lossless_only = detail::measure_model(renderer, cloud.subset(candidates), targets, options);
                    reporter.clock.advance(1);
                }
                row.measure = *lossless_only;
            } else {
                row.measure = detail::measure_model(renderer, cloud.subset(ranking.keep_best(keep)), targets,
                                                          options);
                reporter.clock.advance(1);
            }
            row.dropped = cloud.empty() ? 0.0 : 1.0 - double(row.measure.gaussians) / double(cloud.size());
            row.delta_psnr = row.measure.psnr - result.unpruned.psnr;
            result.rows.push_back(row);
            if (progress.row) progress.row(result.rows.back());
            if (photos && fraction > 0) {
                recovered.push_back(recover_row(renderer, cloud, scores, candidates, keep, method, row, cameras,
                                                *photos, targets, result, options, reporter));
                if (progress.row) progress.row(recovered.back());
            }
        }
        result.rows.insert(result.rows.end(), recovered.begin(), recovered.end());
    };
    for (prune::ScoreMethod method : methods)
        sweep_ranking(std::string(prune::to_string(method)), prune::score(cloud, totals, method, options.seed));
    std::vector<float> cluster_scores;
    if (options.cluster) {
        reporter.step("cluster pruning's stages", 0, 1);
        reporter.clock.begin(Work::scoring_view);
        jobs::ClusterOptions cluster = options.cluster_options;
        if (cluster.views.empty()) cluster.views = result.train_views;
        cluster.settings.background = options.settings.background;
        const auto cluster_start = std::chrono::steady_clock::now();
        cluster_scores = jobs::cluster_gaussian_scores(renderer, renderer.context(), cloud, cameras, cluster);
        result.cluster_seconds = seconds_since(cluster_start);
        reporter.clock.advance(double(cluster_region_views(cluster)));
        reporter.step("cluster pruning's stages", 1, 1);
        sweep_ranking(kClusterMethod, cluster_scores);
    }
    reporter.step("sweep", total_rows, total_rows);

    result.best_method = best_method(result.rows);
    result.sheet_fractions = swept_sheet_fractions(options, fractions);
    const prune::Ranking best_ranking =
        result.best_method == kClusterMethod
            ? prune::Ranking(cluster_scores, candidates)
            : prune::Ranking(prune::score(cloud, totals, prune::parse_score_method(result.best_method), options.seed),
                             candidates);
    folders.create(options.out_dir / "sheets");
    folders.create(options.out_dir / "charts");
    result.sheets = detail::write_sheets(renderer, cloud, best_ranking, result.best_method, result.sheet_fractions, targets,
                                 options, stems, reporter);

    result.csv = fs::absolute(options.out_dir / "sweep.csv");
    result.sh_csv = fs::absolute(options.out_dir / "sh_degrees.csv");
    result.totals = fs::absolute(options.out_dir / "totals.npy");
    result.report = fs::absolute(options.out_dir / "report.html");
    detail::write_sweep_csv(result.csv, result, options.mode);
    detail::write_sh_csv(result.sh_csv, result, options.mode);
    prune::save_totals(totals, result.totals, options.mode);
    const detail::SweepCharts charts = detail::write_sweep_charts(options.out_dir, result, options.mode);
    detail::write_sweep_report(result.report, result, options, charts, options.mode);
    return result;
}

}  // namespace vksplat::sweep
