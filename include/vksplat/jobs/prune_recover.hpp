#pragma once
// Pruning that keeps quality: drop, then re-fit the survivors to the photos (jobs::finetune_scene),
// optionally in rounds as PUP-3DGS does: each round keeps a geometrically smaller share, ranked by
// scores recomputed on the model the previous round re-fitted, and re-fits for its share of the
// iterations. One round is "prune once, then re-fit". What `vksplat prune --recover` runs.
#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "vksplat/jobs/finetune.hpp"
#include "vksplat/prune/scores.hpp"
#include "vksplat/prune/selection.hpp"

namespace vksplat::jobs {

// The defaults are the best of the schedules measured (benchmarks/RESULTS.md, issue 30): five
// rounds, four of them 1,000 steps each and the last re-fitting for the rest, each keeping a
// weighted sample by blend weight, each re-fit decaying the position rate from its initial to its
// final value. H200, bonsai / lego, means of 3 seeds: 80% dropped -0.413 / -0.666 dB with 30,000
// iterations where three equal rounds keeping the best lost -0.564 / -0.940 (one run), and
// -0.196 / -0.649 with the 50,000 default_recover_iterations gives now; 90% -1.637 / -2.749
// against -2.017 / -3.124.
// Iterations of each re-fit round but the last (RecoverOptions::round_spacing says why).
inline constexpr uint64_t kDefaultRoundSpacing = 1000;

struct RecoverOptions {
    // Re-fit iterations in all, split over the rounds (round_iterations); unset: as many as
    // default_recover_iterations gives for the fraction dropped.
    std::optional<uint64_t> iterations;
    // Instead of an iteration count: the wall time of the whole re-fit, in seconds, split over the
    // rounds (round_seconds), each round's share turned into steps by FinetuneOptions::seconds.
    // Refused with `iterations` set, and unless finite and above 0.
    std::optional<double> seconds;
    // Prune-re-fit rounds; unset: recover_rounds's default, fewer where the re-fit is short.
    std::optional<int> rounds;
    // Iterations of each round but the last (0: an equal share of all). The budget recipe settles
    // in rounds 1,000 steps apart and trains the kept Gaussians for the rest of its run; spacing
    // does the same here, so that the last round, the one whose model is kept, re-fits longest
    // (bonsai 80%, 3 rounds: -0.408 dB at 1,000 and -0.411 at 2,000 against -0.564 equal).
    uint64_t round_spacing = kDefaultRoundSpacing;
    // The ranking of rounds after the first. blend-mix re-fits best (5 sampled rounds, means of 3
    // seeds: bonsai 80% -0.060 dB against blend's -0.196 and blend-max's -0.331, 90% -1.199
    // against -1.637 and -1.417; lego 80% -0.388 against -0.649 and -0.362, 90% -2.375 against
    // -2.749 and -2.275).
    prune::ScoreMethod method = prune::ScoreMethod::blend_mix;
    // Every round keeps a weighted random sample of its Gaussians by score (recover_ranking)
    // instead of the best-scored (bonsai, 3 spaced rounds: 80% -0.380 against -0.408, 90% -1.642
    // against -1.793, one run each; over seeds the 80% result spreads by 0.14 dB; 8 rounds lost
    // more than 5 at 80%, -0.493).
    bool sampled = true;
    FinetuneOptions finetune;     // views, rates, loss, background (its iterations are set per round)
    // Applied to the last round's model once it is pruned to its count, before its re-fit, with
    // that model's blend weights over the training views: a size budget drops SH bands here
    // (jobs::prune_scene), so that the longest re-fit adapts the rest to their loss. Dropped after
    // the re-fit instead, nothing made up for them: snowmiku at 0.9 MB lost 0.461 dB that way.
    std::function<GaussianCloud(const GaussianCloud& model, std::span<const double> blend)> before_last_refit;

    RecoverOptions() { finetune.train.position_schedule = train::PositionSchedule::decay; }
};

struct RecoverRound {
    size_t kept = 0;
    FinetuneResult refit;         // its cloud is the round's model
};

struct RecoverResult {
    GaussianCloud cloud;          // the last round's re-fitted model
    std::vector<RecoverRound> rounds;
};

// The rounds a re-fit of `iterations` steps runs: options.rounds where set; otherwise
// kDefaultRecoverRounds, but one per round_spacing steps (kDefaultRoundSpacing where spacing is
// 0) where the re-fit is shorter, so that the round whose model is kept re-fits at least that long
// (snowmiku at 0.9 MB, 300 iterations, the same choice of 37,274 Gaussians: five rounds of 60
// steps lost 0.535 dB, one round of 300 0.461; one run each). A time budget (options.seconds)
// keeps the five: its steps are not known ahead, and its last round takes what the early ones
// leave (round_seconds).
inline constexpr int kDefaultRecoverRounds = 5;
int recover_rounds(const RecoverOptions& options, uint64_t iterations);

// The kept count of round r (1-based) of `rounds` from n Gaussians down to `target`: n (target/n)^(r/rounds).
size_t round_target(size_t n, size_t target, int round, int rounds);
// The re-fit iterations of round r (1-based): `iterations` split as evenly as whole steps allow,
// the first rounds taking one more where they do not divide, so that the rounds add up to it.
// With `spacing` > 0, every round but the last takes that many (while iterations last: each round
// at least one) and the last the rest.
uint64_t round_iterations(uint64_t iterations, int round, int rounds, uint64_t spacing = 0);

// The re-fit iterations in all of pruning `n` Gaussians to `kept`: options.iterations, else
// default_recover_iterations of the fraction dropped.
uint64_t recover_iterations(const RecoverOptions& options, size_t n, size_t kept);

// The re-fit of one round that prunes `n` Gaussians to `kept`: options.finetune with
// recover_iterations or, with options.seconds, that time budget. What each probe of a quality
// budget runs.
FinetuneOptions single_refit(const RecoverOptions& options, size_t n, size_t kept);

// The re-fit iterations when none are asked for, by the fraction of the Gaussians dropped (0..1):
// 5,000 up to half dropped, then rising linearly to 50,000 at 80% and 60,000 at 90% and beyond,
// in whole thousands. Measured on bonsai (issue 30, H200): every doubling gained about 0.22 dB at
// 80% and 0.29 at 90%, with no sign of levelling off; with the default rounds, 80% dropped lost
// 0.361 / 0.261 / 0.161 dB at 30,000 / 40,000 / 50,000 (seed 0), and 50,000 over seeds 0-2
// -0.196 on average in 58.6 s on an H200 (the 60 s a re-fit); 90% with 60,000 took 58.4 s.
uint64_t default_recover_iterations(double dropped);

// The seconds round r (1-based) of `rounds` may take when `remaining` seconds of the budget are
// left as it starts: an equal share of what is left, so that time the earlier rounds overran (or
// the scoring between rounds took) comes out of the later ones and the whole stays in the budget.
// Spaced rounds (RecoverOptions::round_spacing > 0) are short but for the last: each earlier one
// takes at most kSpacedRoundShare of what is left (a time budget cannot count their steps ahead).
inline constexpr double kSpacedRoundShare = 0.05;
double round_seconds(double remaining, int round, int rounds, bool spaced = false);

// What prune_and_recover would refuse, found without its work: rounds < 1, a resume of several
// rounds, no iterations per round, a time budget that is not a positive number of seconds or comes
// with an iteration count, and a missing or mis-sized photo of a training view (each read
// through checked_photo). For commands to call before they score the views, which takes minutes on
// a real scene, so that a bad photo is not found only after.
void check_recover(const RecoverOptions& options, const std::vector<Camera>& cameras, const PhotoSource& photos);

// How a round ranks its model's Gaussians from their scores and candidates: by score, or with
// options.sampled by prune::sampling_keys seeded by finetune.seed and the round (1-based).
prune::Ranking recover_ranking(std::span<const float> scores, std::span<const uint8_t> candidates,
                               const RecoverOptions& options, int round);

// `scores` and `candidates` rank the Gaussians of `cloud` (the unpruned model) for the first round
// (recover_ranking); `keep` is the final count. Throws InputError for what check_recover refuses.
RecoverResult prune_and_recover(const gpu::Context& context, Renderer& renderer, const GaussianCloud& cloud,
                                std::span<const float> scores, std::span<const uint8_t> candidates, size_t keep,
                                const std::vector<Camera>& cameras,
                                const PhotoSource& photos, const RecoverOptions& options,
                                const QualityProbe& quality = {},
                                const std::function<void(int round, const train::LoopStatus&)>& progress = {});

}  // namespace vksplat::jobs
