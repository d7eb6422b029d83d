// Prune, re-fit, and (in rounds) prune the re-fitted model again.
#include "vksplat/jobs/prune_recover.hpp"

#include <cmath>

#include "vksplat/error.hpp"
#include "vksplat/jobs/view_selection.hpp"
#include "vksplat/prune/accumulate.hpp"

namespace vksplat::jobs {

size_t round_target(size_t n, size_t target, int round, int rounds) {
    if (round >= rounds || n == 0) return target;
    const double share = std::pow(double(target) / double(n), double(round) / double(rounds));
    return std::max(target, static_cast<size_t>(std::llround(double(n) * share)));
}

namespace {

// Throws InputError for options no round can run with.
void check_rounds(const RecoverOptions& options) {
    if (options.rounds < 1) throw InputError("--rounds " + std::to_string(options.rounds), "must be 1 or more");
    if (options.rounds > 1 && options.finetune.resume)
        throw InputError("--resume", "continues one re-fit; it cannot resume a run of several rounds");
    if (options.iterations < uint64_t(options.rounds))
        throw InputError("--recover " + std::to_string(options.iterations),
                         "leaves no iterations for each of " + std::to_string(options.rounds) + " rounds");
}

}  // namespace

uint64_t round_iterations(uint64_t iterations, int round, int rounds) {
    const auto n = uint64_t(rounds), r = uint64_t(round);
    return iterations / n + (r <= iterations % n ? 1 : 0);
}

void check_recover(const RecoverOptions& options, const std::vector<Camera>& cameras, const PhotoSource& photos) {
    check_rounds(options);
    const FinetuneOptions& finetune = options.finetune;
    for (size_t view : split_views(cameras, finetune.test_views, finetune.train_views).train)
        checked_photo(photos, cameras[view]);
}

RecoverResult prune_and_recover(const gpu::Context& context, Renderer& renderer, const GaussianCloud& cloud,
                                const prune::Ranking& ranking, size_t keep, const std::vector<Camera>& cameras,
                                const PhotoSource& photos, const RecoverOptions& options, const QualityProbe& quality,
                                const std::function<void(int round, const train::LoopStatus&)>& progress) {
    check_rounds(options);
    FinetuneOptions finetune = options.finetune;
    const std::vector<size_t> train = split_views(cameras, finetune.test_views, finetune.train_views).train;
    RenderSettings settings;
    settings.background = finetune.train.background;
    settings.max_sh_degree = finetune.train.sh_degree;

    RecoverResult result;
    GaussianCloud model = cloud.subset(ranking.keep_best(round_target(cloud.size(), keep, 1, options.rounds)));
    for (int round = 1;; ++round) {
        RecoverRound done;
        done.kept = model.size();
        // Only the last round's model is measured: the others are intermediate.
        const bool last = round == options.rounds;
        finetune.iterations = round_iterations(options.iterations, round, options.rounds);
        done.refit = finetune_scene(context, model, cameras, photos, finetune, last ? quality : QualityProbe{},
                                    [&](const train::LoopStatus& s) {
                                        if (progress) progress(round, s);
                                    });
        model = std::move(done.refit.cloud);
        result.rounds.push_back(std::move(done));
        if (last || result.rounds.back().refit.interrupted) break;
        // The next round ranks the re-fitted model by its own contributions now.
        const prune::ViewTotals totals = prune::accumulate(renderer, model, cameras, train, settings);
        const prune::Ranking next(prune::score(model, totals, options.method), prune::lossless_mask(totals));
        model = model.subset(next.keep_best(round_target(cloud.size(), keep, round + 1, options.rounds)));
    }
    result.cloud = std::move(model);
    return result;
}

}  // namespace vksplat::jobs
