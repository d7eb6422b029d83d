#pragma once
// Settling: once densification ends, the Gaussians that contribute least to the training views are
// removed in rounds and the rest train on, as Mini-Splatting and Speedy-Splat prune inside training.
// The budget recipe settles its peak down to the budget (BudgetStrategy); the lean recipe settles
// the reference's growth to the Gaussians that carry a share of the importance (ReferenceStrategy
// with a Settling), so that a scene whose densification over-fits keeps only what its pictures
// need: snowmiku grows 446,866 Gaussians at the reference's threshold and scores 28.21 dB, and
// 28.64 dB with the 125,889 that carry 99% (jobs::LeanRecipe).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "vksplat/scene/scene.hpp"
#include "vksplat/train/trainer.hpp"

namespace vksplat::train {

// Per Gaussian of a scene, how much it is worth keeping (higher: more; e.g. blend weight Sum alpha T
// over the training views).
using Importance = std::function<std::vector<float>(const GaussianCloud&)>;

// The `count` Gaussians of the highest importance (ties broken by index, so the choice is the same
// on every platform; NaN ranks lowest; at least one is kept).
std::vector<uint8_t> keep_most_important(const std::vector<float>& importance, size_t count);

// The fewest Gaussians, the most important first, whose importance sums to at least `share` of
// the total (share in (0, 1]; NaN and negative importance count as 0; at least one).
size_t count_carrying(const std::vector<float>& importance, double share);

// The count a settling round keeps of `count` Gaussians with `rounds_left` rounds to go (this one
// included): budget x (count / budget)^((rounds_left - 1) / rounds_left), the budget itself in the
// last round and whenever count is within it.
size_t settle_target(size_t count, size_t budget, int rounds_left);

// What a strategy removed by importance, for the log and metrics.
struct ImportancePrunes {
    size_t pruned = 0;          // removed by importance, in all (the settling included)
    uint64_t prune_events = 0;
    double importance_seconds = 0;  // spent scoring
};

// Scores the trainer's Gaussians (its frame released first: Trainer::release_frame) and keeps the
// `keep(scores)` most important.
void remove_least_important(Trainer& trainer, const Importance& importance, ImportancePrunes& events,
                            const std::function<size_t(const std::vector<float>&)>& keep);

struct SettleSchedule {
    uint64_t at = 15000;           // the first round, after this step
    // Rounds `spacing` steps apart, each keeping an equal share (geometric) of the way to the
    // target, as the re-fits of issue 30 lost less when pruned in three rounds than in one. A short
    // run settles in rounds closer together, or at once where none fits.
    int rounds = 3;
    uint64_t spacing = 1000;
    // From `at` on, the position rate decays afresh from its initial rate to the end of the run
    // (Trainer::set_position_decay), as a re-fit of a pruned scene does, so that what is kept can
    // move into the gaps the settling leaves.
    bool restart_decay = true;
    uint64_t iterations = 30000;   // the run's length: the restarted decay and the rounds end there
};

// Where settling leads: a count (the budget recipe's budget), or, with `share` > 0, the Gaussians
// that carry that share of the importance, counted afresh each round on the scene as it has
// re-fitted (so a resumed run needs nothing remembered).
struct SettleTarget {
    size_t budget = 0;
    double share = 0;
};

class Settling {
public:
    Settling(SettleSchedule schedule, SettleTarget target, Importance importance);
    void before_step(Trainer& trainer, uint64_t iteration) const;
    void after_step(Trainer& trainer, uint64_t iteration, ImportancePrunes& events) const;

private:
    SettleSchedule schedule_;
    SettleTarget target_;
    Importance importance_;
};

}  // namespace vksplat::train
