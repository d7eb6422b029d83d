// Prune, re-fit, and (in rounds) prune the re-fitted model again.
#include "vksplat/jobs/prune_recover.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>

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
    if (options.rounds && *options.rounds < 1)
        throw InputError("--rounds " + std::to_string(*options.rounds), "must be 1 or more");
    if (options.rounds.value_or(1) > 1 && options.finetune.resume)
        throw InputError("--resume", "continues one re-fit; it cannot resume a run of several rounds");
    if (options.seconds) {
        char text[32];
        std::snprintf(text, sizeof(text), "%g", *options.seconds);
        const std::string what = std::string("--recover-seconds ") + text;
        if (!std::isfinite(*options.seconds) || *options.seconds <= 0)
            throw InputError(what, "must be a finite number of seconds above 0");
        if (options.iterations)
            throw InputError(what, "is a budget instead of an iteration count: give --recover " +
                                       std::to_string(*options.iterations) + " or the seconds, not both");
    }
    if (options.iterations && options.rounds && *options.iterations < uint64_t(*options.rounds))
        throw InputError("--recover " + std::to_string(*options.iterations),
                         "leaves no iterations for each of " + std::to_string(*options.rounds) + " rounds");
}

double dropped_share(size_t n, size_t kept) { return n == 0 ? 0.0 : 1.0 - double(kept) / double(n); }

}  // namespace

int recover_rounds(const RecoverOptions& options, uint64_t iterations) {
    if (options.rounds) return *options.rounds;
    // A resumed re-fit continues one round (check_rounds refuses several).
    if (options.finetune.resume) return 1;
    if (options.seconds) return kDefaultRecoverRounds;
    const uint64_t unit = options.round_spacing > 0 ? options.round_spacing : kDefaultRoundSpacing;
    return int(std::clamp<uint64_t>(iterations / unit, 1, kDefaultRecoverRounds));
}

uint64_t round_iterations(uint64_t iterations, int round, int rounds, uint64_t spacing) {
    const auto n = uint64_t(rounds), r = uint64_t(round);
    if (spacing == 0 || n < 2) return iterations / n + (r <= iterations % n ? 1 : 0);
    // At most an equal share each, so that the last round is never shorter than an early one and
    // every round gets a step (check_rounds refuses fewer iterations than rounds).
    const uint64_t early = std::max<uint64_t>(1, std::min(spacing, iterations / n));
    return r < n ? early : iterations - early * (n - 1);
}

uint64_t default_recover_iterations(double dropped) {
    // (fraction dropped, iterations), joined by straight lines; flat beyond the last.
    constexpr std::array<std::pair<double, double>, 3> kKnots{{{0.5, 5000}, {0.8, 50000}, {0.9, 60000}}};
    if (!(dropped > kKnots.front().first)) return uint64_t(kKnots.front().second);
    for (size_t i = 1; i < kKnots.size(); ++i) {
        const auto [x0, y0] = kKnots[i - 1];
        const auto [x1, y1] = kKnots[i];
        if (dropped < x1) return uint64_t(std::llround((y0 + (y1 - y0) * (dropped - x0) / (x1 - x0)) / 1000.0)) * 1000;
    }
    return uint64_t(kKnots.back().second);
}

double round_seconds(double remaining, int round, int rounds, bool spaced) {
    const double equal = remaining / double(rounds - round + 1);
    return spaced && round < rounds ? std::min(equal, kSpacedRoundShare * remaining) : equal;
}

uint64_t recover_iterations(const RecoverOptions& options, size_t n, size_t kept) {
    return options.iterations.value_or(default_recover_iterations(dropped_share(n, kept)));
}

FinetuneOptions single_refit(const RecoverOptions& options, size_t n, size_t kept) {
    FinetuneOptions finetune = options.finetune;
    finetune.seconds = options.seconds;
    finetune.iterations = recover_iterations(options, n, kept);
    return finetune;
}

void check_recover(const RecoverOptions& options, const std::vector<Camera>& cameras, const PhotoSource& photos) {
    check_rounds(options);
    const FinetuneOptions& finetune = options.finetune;
    for (size_t view : split_views(cameras, finetune.test_views, finetune.train_views).train)
        checked_photo(photos, cameras[view]);
}

prune::Ranking recover_ranking(std::span<const float> scores, std::span<const uint8_t> candidates,
                               const RecoverOptions& options, int round) {
    if (!options.sampled) return prune::Ranking(scores, candidates);
    return prune::Ranking(
        prune::sampling_keys(prune::sampling_weights(scores, options.method), options.finetune.seed + uint64_t(round)),
        candidates);
}

RecoverResult prune_and_recover(const gpu::Context& context, Renderer& renderer, const GaussianCloud& cloud,
                                std::span<const float> scores, std::span<const uint8_t> candidates, size_t keep,
                                const std::vector<Camera>& cameras,
                                const PhotoSource& photos, const RecoverOptions& options, const QualityProbe& quality,
                                const std::function<void(int round, const train::LoopStatus&)>& progress) {
    check_rounds(options);
    FinetuneOptions finetune = options.finetune;
    const std::vector<size_t> train = split_views(cameras, finetune.test_views, finetune.train_views).train;
    RenderSettings settings;
    settings.background = finetune.train.background;
    settings.max_sh_degree = finetune.train.sh_degree;

    const auto start = std::chrono::steady_clock::now();
    const uint64_t iterations = recover_iterations(options, cloud.size(), keep);
    const int rounds = recover_rounds(options, iterations);
    RecoverResult result;
    const prune::Ranking first = recover_ranking(scores, candidates, options, 1);
    GaussianCloud model = cloud.subset(first.keep_best(round_target(cloud.size(), keep, 1, rounds)));
    for (int round = 1;; ++round) {
        RecoverRound done;
        done.kept = model.size();
        // Only the last round's model is measured: the others are intermediate.
        const bool last = round == rounds;
        if (last && options.before_last_refit)
            model = options.before_last_refit(model, prune::accumulate(renderer, model, cameras, train, settings).blend);
        if (options.seconds) {
            const double spent = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            // A round the earlier ones left no time still takes its one step (planned_iterations).
            const double share =
                round_seconds(*options.seconds - spent, round, rounds, options.round_spacing > 0);
            finetune.seconds = std::max(share, 1e-3);
        } else {
            finetune.seconds.reset();
            finetune.iterations = round_iterations(iterations, round, rounds, options.round_spacing);
        }
        done.refit = finetune_scene(context, model, cameras, photos, finetune, last ? quality : QualityProbe{},
                                    [&](const train::LoopStatus& s) {
                                        if (progress) progress(round, s);
                                    });
        model = std::move(done.refit.cloud);
        result.rounds.push_back(std::move(done));
        if (last || result.rounds.back().refit.interrupted) break;
        // The next round ranks the re-fitted model by its own contributions now.
        const prune::ViewTotals totals =
            prune::accumulate(renderer, model, cameras, train, settings, {}, prune::needs_fisher(options.method));
        const prune::Ranking next = recover_ranking(prune::score(model, totals, options.method),
                                                    prune::lossless_mask(totals), options, round + 1);
        model = model.subset(next.keep_best(round_target(cloud.size(), keep, round + 1, rounds)));
    }
    result.cloud = std::move(model);
    return result;
}

}  // namespace vksplat::jobs
