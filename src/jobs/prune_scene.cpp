// The prune job: sanitise, score (or load scores), select, measure on the test views, write.
#include "vksplat/jobs/prune_scene.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <span>
#include <string>

#include "vksplat/error.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/prune/score_files.hpp"
#include "vksplat/prune/selection.hpp"
#include "vksplat/prune/sh_reduction.hpp"

namespace vksplat::jobs {
namespace {

namespace fs = std::filesystem;

// Refusals that need no rendering, made before any (the selectors and writers check again).
void check_options(const PruneOptions& options) {
    if (options.out.empty()) throw InputError("prune", "no output file given");
    // Every output checked before minutes of rendering (the writers check again), and none may be
    // a file the job reads: the scene, its cameras, a scores file.
    std::vector<fs::path> inputs = options.inputs;
    if (options.load_scores) inputs.push_back(*options.load_scores);
    io::refuse_input_as_output(options.out, inputs);
    io::check_scene_writable(options.out, options.mode);  // a format its name says, and a file that may be written
    for (const auto& path : {options.save_scores, options.save_totals}) {
        if (!path) continue;
        io::refuse_input_as_output(*path, inputs);
        io::check_writable(*path, options.mode);
    }
    if (options.sh_degree && (*options.sh_degree < 0 || *options.sh_degree > 3))
        throw InputError("--sh-degree " + std::to_string(*options.sh_degree), "must lie in 0..3");
    if (options.sh_precision) prune::check_sh_precision(*options.sh_precision);
    if (const auto* ratio = std::get_if<DropRatio>(&options.selector); ratio && !(ratio->ratio >= 0 && ratio->ratio <= 1))
        throw InputError("--ratio " + std::to_string(ratio->ratio), "must lie in [0, 1] (the fraction to drop)");
    if (const auto* threshold = std::get_if<DropAtOrBelow>(&options.selector); threshold && std::isnan(threshold->threshold))
        throw InputError("--threshold", "must be a number");
    if (const auto* budget = std::get_if<prune::QualityBudget>(&options.selector); budget && !(budget->max_psnr_drop >= 0))
        throw InputError("--max-psnr-drop " + std::to_string(budget->max_psnr_drop), "must be 0 or more (dB)");
    if (options.recover && !options.images_dir && !options.photos)
        throw InputError("--recover", "re-fits to the photos: give them with --images");
    if (options.recover && options.recover->rounds.value_or(1) != 1 &&
        std::holds_alternative<prune::QualityBudget>(options.selector))
        throw InputError("--rounds " + std::to_string(*options.recover->rounds),
                         "a quality budget re-fits each probe once: use one round with --max-psnr-drop");
}

// The size budget of options.selector in the output's format and SH precision (prune/size_budget.hpp).
std::optional<prune::SizeBudget> size_budget(const PruneOptions& options) {
    const auto* size = std::get_if<prune::SizeBudget>(&options.selector);
    if (!size) return std::nullopt;
    prune::SizeBudget budget = *size;
    budget.format = io::scene_format_named(options.out);
    if (options.sh_precision) budget.sh_precision = *options.sh_precision;
    return budget;
}

// The scores, the Gaussians still in play after the lossless pass, and the totals behind both
// (absent when a scores file was loaded: it carries no pixel counts, so no lossless pass).
struct Scored {
    std::vector<float> scores;
    prune::KeepMask candidates;
    std::optional<prune::ViewTotals> totals;
};

Scored score_from_file(const GaussianCloud& cloud, const PruneOptions& options) {
    prune::ScoreFile file = prune::load_score_file(*options.load_scores);
    if (file.size() != cloud.size())
        throw InputError(options.load_scores->string(), "holds " + std::to_string(file.size()) +
                                                            " Gaussians' scores, the scene has " +
                                                            std::to_string(cloud.size()) + " (after sanitising)");
    if (file.scores) return {std::move(*file.scores), prune::keep_all(cloud.size()), std::nullopt};
    return {prune::score(cloud, *file.totals, score_method_of(options), options.seed),
            prune::lossless_mask(*file.totals),
            std::move(file.totals)};
}

Scored score_from_views(Renderer& renderer, const GaussianCloud& cloud, const std::vector<Camera>& cameras,
                        const PruneOptions& options, const std::vector<size_t>& train, const prune::Progress& progress) {
    // Rendered even for opacity and random: the lossless pass needs the pixel counts.
    prune::ViewTotals totals = prune::accumulate(renderer, cloud, cameras, train, options.settings, progress,
                                                 prune::needs_fisher(score_method_of(options)));
    return {prune::score(cloud, totals, score_method_of(options), options.seed), prune::lossless_mask(totals),
            std::move(totals)};
}

void save_scored(const Scored& scored, const PruneOptions& options) {
    if (options.save_scores) prune::save_scores(scored.scores, *options.save_scores, options.mode);
    if (!options.save_totals) return;
    if (!scored.totals)
        throw InputError(options.load_scores->string(), "holds scores, not view totals: there are no totals to save");
    prune::save_totals(*scored.totals, *options.save_totals, options.mode);
}

std::vector<Camera> pick(const std::vector<Camera>& cameras, const std::vector<size_t>& views) {
    std::vector<Camera> picked;
    for (size_t v : views) picked.push_back(cameras[v]);
    return picked;
}

// What SH bands cost for the size budget (sh_reduction.hpp): the blend weights, where scored.
std::span<const double> blend_weights(const Scored& scored) {
    return scored.totals ? std::span<const double>(scored.totals->blend) : std::span<const double>();
}

// The keep mask the selector asks for; a quality budget also leaves its probes in `result`.
prune::KeepMask select(PruneResult& result, Renderer& renderer, const GaussianCloud& cloud, const Scored& scored,
                       const eval::TestViews& targets, const PruneOptions& options, const PruneProgress& progress) {
    if (const auto* threshold = std::get_if<DropAtOrBelow>(&options.selector))
        return prune::select_threshold(scored.scores, threshold->threshold, scored.candidates);
    if (const auto* ratio = std::get_if<DropRatio>(&options.selector))
        return prune::select_ratio(scored.scores, ratio->ratio, scored.candidates);
    if (const auto* count = std::get_if<KeepCount>(&options.selector))
        return prune::select_count(scored.scores, count->count, scored.candidates);
    if (const auto size = size_budget(options)) {
        result.budget = prune::fit_size_budget(renderer, cloud, prune::Ranking(scored.scores, scored.candidates),
                                               blend_weights(scored), targets, *size, options.settings, progress.probe);
        return result.budget->keep;
    }
    result.budget = prune::fit_quality_budget(renderer, cloud, prune::Ranking(scored.scores, scored.candidates), targets,
                                              std::get<prune::QualityBudget>(options.selector), options.settings,
                                              progress.probe);
    return result.budget->keep;
}

// options.recover with the job's method, views and background.
RecoverOptions recover_options(const PruneOptions& options, const PruneResult& result) {
    RecoverOptions recover = *options.recover;
    recover.method = score_method_of(options);
    recover.finetune.test_views = result.test_views;
    recover.finetune.train_views = result.train_views;
    recover.finetune.train.background = options.settings.background;
    return recover;
}

PhotoSource recover_photos(const PruneOptions& options) {
    if (options.photos) return options.photos;
    return photos_in_folder(*options.images_dir, options.settings.background);
}

// The test views' photos as quality targets: from options.photos, else from images_dir.
eval::TestViews photo_targets(const std::vector<Camera>& cameras, const PruneOptions& options) {
    if (!options.photos) return eval::photo_targets(cameras, *options.images_dir, options.settings.background);
    eval::TestViews views;
    views.cameras = cameras;
    views.photos = true;
    for (const Camera& camera : cameras) views.targets.push_back(checked_photo(options.photos, camera).rgb);
    return views;
}

// What each round of a re-fit kept and took, for the report.
void report_rounds(PruneResult& result, const RecoverResult& recovered) {
    for (const auto& round : recovered.rounds)
        result.recover_rounds.push_back({round.kept, round.refit.iterations, round.refit.seconds});
}

// A size budget's short re-fit (of its shortlisted candidates, and of what its fit cut): one round
// of a tenth of the iterations a re-fit from n Gaussians to `kept` takes, at least one.
FinetuneOptions short_refit(const RecoverOptions& recover, size_t n, size_t kept) {
    FinetuneOptions shortened = single_refit(recover, n, kept);
    shortened.seconds.reset();
    shortened.iterations = std::max<uint64_t>(1, recover_iterations(recover, n, kept) / 10);
    return shortened;
}

// The size budget's choice (result.budget) re-fitted: its count reached in the rounds asked for
// from the cloud at the chosen model's degree, its share of bands per Gaussian dropped before the
// last round's re-fit (RecoverOptions::before_last_refit), then dropped again by the re-fitted
// coefficients (the re-fit gives the dropped bands some colour back, which the file would pay
// for) and its least Gaussians, if need be, until the file fits (prune::fit_refitted).
GaussianCloud refit_size_choice(PruneResult& result, Renderer& renderer, const GaussianCloud& cloud,
                                const std::vector<Camera>& cameras, const Scored& scored, const PhotoSource& photos,
                                const RecoverOptions& recover, const prune::SizeBudget& size,
                                const PruneOptions& options, const PruneProgress& progress) {
    const prune::BudgetResult& choice = *result.budget;
    const GaussianCloud start = choice.sh_degree < cloud.sh_degree ? cloud.with_sh_degree(choice.sh_degree) : cloud;
    const double sh_share = prune::model_sh_share(choice, cloud.sh_degree);
    RecoverOptions rounds = recover;
    if (sh_share > 0.0)
        rounds.before_last_refit = [sh_share](const GaussianCloud& model, std::span<const double> blend) {
            return prune::with_sh_share_dropped(model, blend, sh_share);
        };
    RecoverResult recovered = prune_and_recover(renderer.context(), renderer, start, scored.scores, scored.candidates,
                                                choice.kept, cameras, photos, rounds, {}, progress.refit);
    report_rounds(result, recovered);
    prune::SizeBudget chosen = size;
    chosen.sh_precision = choice.sh_precision;
    // Which bands cost least and which Gaussians go first if the file outgrows the budget, by the
    // re-fitted model's own blend weights: its Gaussians are not the choice's (the rounds re-rank
    // and sample), and one scoring pass costs less than a round's re-fit.
    const auto fit = [&](const GaussianCloud& refitted) {
        const prune::ViewTotals totals = prune::accumulate(renderer, refitted, cameras, result.train_views,
                                                           options.settings, {},
                                                           prune::needs_fisher(score_method_of(options)));
        return prune::fit_refitted(refitted, totals.blend,
                                   prune::score(refitted, totals, score_method_of(options), options.seed), sh_share,
                                   chosen);
    };
    GaussianCloud fitted = fit(recovered.cloud);
    if (fitted.size() == recovered.cloud.size()) return fitted;
    // The long re-fit grew the file more than the candidates' short ones foresaw (bonsai at 3 MB:
    // 86,891 Gaussians re-fitted, 80,715 fitted, -0.500 dB): what is left gets a short re-fit of
    // its own (a tenth of the iterations, as the candidates had) to make up for those that went,
    // and the file is fitted again.
    const FinetuneOptions settle = short_refit(recover, cloud.size(), choice.kept);
    const FinetuneResult settled = finetune_scene(renderer.context(), fitted, cameras, photos, settle, {},
                                                  [&](const train::LoopStatus& s) {
                                                      if (progress.refit) progress.refit(kRefitAfterFit, s);
                                                  });
    result.recover_rounds.push_back({fitted.size(), settled.iterations, settled.seconds, true});
    return fit(settled.cloud);
}

// Prune and re-fit (options.recover): with a quality budget, every probe is re-fitted (one round)
// before it is measured; with a size budget, the count and SH bands chosen are reached in the
// rounds asked for; otherwise the selector's count is.
GaussianCloud recover(PruneResult& result, Renderer& renderer, const GaussianCloud& cloud,
                      const std::vector<Camera>& cameras, const Scored& scored, const eval::TestViews& targets,
                      const PruneOptions& options, const PruneProgress& progress) {
    const RecoverOptions recover = recover_options(options, result);
    const PhotoSource photos = recover_photos(options);
    const gpu::Context& context = renderer.context();
    if (auto budget = std::get_if<prune::QualityBudget>(&options.selector)) {
        // One round per probe: the bisection re-fits every probe it measures, so rounds (each
        // scoring every training view again) would multiply the whole search's cost.
        prune::QualityBudget refitted = *budget;
        refitted.refit = [&](const GaussianCloud& model) {
            return finetune_scene(context, model, cameras, photos, single_refit(recover, cloud.size(), model.size()), {},
                                  [&](const train::LoopStatus& s) {
                                      if (progress.refit) progress.refit(1, s);
                                  })
                .cloud;
        };
        result.budget = prune::fit_quality_budget(renderer, cloud, prune::Ranking(scored.scores, scored.candidates),
                                                  targets, refitted, options.settings, progress.probe);
        return result.budget->model ? std::move(*result.budget->model) : cloud.subset(result.budget->keep);
    }
    if (auto size = size_budget(options)) {
        // The shortlist's re-fits: one round of a tenth of the re-fit's iterations each (at least
        // one), enough to tell which candidates a re-fit favours, at a fraction of its cost.
        size->refit = [&](const GaussianCloud& model) {
            return finetune_scene(context, model, cameras, photos, short_refit(recover, cloud.size(), model.size()), {},
                                  [&](const train::LoopStatus& s) {
                                      if (progress.refit) progress.refit(0, s);
                                  })
                .cloud;
        };
        result.budget = prune::fit_size_budget(renderer, cloud, prune::Ranking(scored.scores, scored.candidates),
                                               blend_weights(scored), targets, *size, options.settings, progress.probe);
        result.budget->model.reset();  // un-refitted: the rounds start again from the cloud
        return refit_size_choice(result, renderer, cloud, cameras, scored, photos, recover, *size, options, progress);
    }
    const size_t keep = prune::count_kept(select(result, renderer, cloud, scored, targets, options, progress));
    RecoverResult recovered = prune_and_recover(context, renderer, cloud, scored.scores, scored.candidates, keep,
                                                cameras, photos, recover, {}, progress.refit);
    report_rounds(result, recovered);
    return std::move(recovered.cloud);
}

}  // namespace

prune::ScoreMethod score_method_of(const PruneOptions& options) {
    if (options.method) return *options.method;
    return options.recover ? prune::ScoreMethod::blend_mix : prune::ScoreMethod::blend;
}

PruneResult prune_scene(Renderer& renderer, const GaussianCloud& input, const std::vector<Camera>& cameras,
                        const PruneOptions& options, const PruneProgress& progress) {
    check_options(options);
    PruneResult result;
    ViewSplit split = split_views(cameras, options.test_views, options.train_views);
    result.test_views = std::move(split.test);
    result.train_views = std::move(split.train);
    // The re-fit's options and photos too, so that a bad one is not found after minutes of scoring.
    if (options.recover) check_recover(recover_options(options, result), cameras, recover_photos(options));

    // Sanitised once here, so that scores, masks and the output all index the same Gaussians.
    GaussianCloud cloud = input;
    result.sanitize = sanitize(cloud);
    result.count_before = cloud.size();
    result.bytes_before = cloud.ply_bytes();
    result.sh_degree_before = cloud.sh_degree;
    // A size no model reaches is refused before any rendering (one Gaussian at degree 0 is the least).
    if (const auto size = size_budget(options)) {
        prune::KeepMask first(cloud.size(), 0);
        if (!first.empty()) first[0] = 1;
        prune::check_size_reachable(cloud.subset(first).with_sh_degree(0), *size);
    }

    // Photos are read before the long part, so that a missing one is reported at once.
    const std::vector<Camera> test_cameras = pick(cameras, result.test_views);
    result.against_photos = options.images_dir || options.photos;
    const eval::TestViews targets = result.against_photos
                                         ? photo_targets(test_cameras, options)
                                         : eval::render_targets(renderer, cloud, test_cameras, options.settings);
    if (result.against_photos) result.before = eval::measure_quality(renderer, cloud, targets, options.settings, true);

    const auto start = std::chrono::steady_clock::now();
    const Scored scored = options.load_scores
                              ? score_from_file(cloud, options)
                              : score_from_views(renderer, cloud, cameras, options, result.train_views, progress.scoring);
    if (!options.load_scores)
        result.scoring_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    save_scored(scored, options);
    result.lossless_applied = scored.totals.has_value();
    result.lossless_dropped = cloud.size() - prune::count_kept(scored.candidates);

    // From here on the scene is at the degree asked for: what every selector cuts down.
    if (options.sh_degree && *options.sh_degree < cloud.sh_degree) cloud = cloud.with_sh_degree(*options.sh_degree);
    GaussianCloud pruned;
    if (!options.recover) {
        pruned = cloud.subset(select(result, renderer, cloud, scored, targets, options, progress));
        if (result.budget && result.budget->model)  // a size budget's: SH bands dropped per Gaussian
            pruned = std::move(*result.budget->model);
        else if (result.budget && result.budget->sh_degree < pruned.sh_degree)
            pruned = pruned.with_sh_degree(result.budget->sh_degree);
    } else {
        pruned = recover(result, renderer, cloud, cameras, scored, targets, options, progress);
    }
    if (options.sh_precision) pruned = prune::with_sh_precision(pruned, *options.sh_precision);
    result.sh_degree_after = pruned.sh_degree;
    result.count_after = pruned.size();
    result.after = eval::measure_quality(renderer, pruned, targets, options.settings, true);
    io::write_scene(pruned, options.out, options.mode);
    result.bytes_after = fs::file_size(options.out);
    return result;
}

}  // namespace vksplat::jobs
