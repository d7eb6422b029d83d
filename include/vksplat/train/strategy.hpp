#pragma once
// What a training run does around its steps, apart from the step itself: which SH bands a step
// evaluates, and when the scene's Gaussians are cloned, split, pruned or have their opacity reset.
// The one training loop (training_loop.hpp) asks its strategy before and after every step, as
// gsplat's strategies are asked; `train`, `finetune` and `prune --recover` differ in the strategy
// they give it, not in their loops.
#include <cstdint>
#include <optional>

#include "vksplat/train/settling.hpp"
#include "vksplat/train/trainer.hpp"

namespace vksplat::train {

class Strategy {
public:
    virtual ~Strategy() = default;
    // Before step `iteration` (counted from 1, as the reference counts).
    virtual void before_step(Trainer& trainer, uint64_t iteration) = 0;
    // After it is submitted (Trainer::submit; it may still run: whatever reads or changes the scene
    // waits for it): densification and opacity resets happen here.
    virtual void after_step(Trainer& trainer, uint64_t iteration) = 0;
};

// Re-fitting a trained scene: every SH band the trainer was made with from the first step, the
// Gaussians as they are (finetune, prune --recover).
class RefitStrategy final : public Strategy {
public:
    void before_step(Trainer&, uint64_t) override {}
    void after_step(Trainer&, uint64_t) override {}
};

// The reference 3DGS recipe's schedule (Kerbl et al. 2023, train.py), each constant its default:
// one more SH band every 1,000 iterations; densification (DensifyRules) every 100 iterations after
// 500 and before 15,000, pruning the oversized only after the first opacity reset; opacity reset
// every 3,000 iterations before 15,000, and at 500 on a white background.
struct ReferenceSchedule {
    int sh_degree = 3;
    uint64_t sh_degree_interval = 1000;
    uint64_t densify_from = 500, densify_until = 15000, densify_interval = 100;
    uint64_t opacity_reset_interval = 3000;
    double opacity_reset_value = 0.01;
    // Threshold 0.0002, percent dense 0.01, min opacity 0.005, no screen-size prune; prune_large is
    // set by the strategy after the first opacity reset.
    DensifyRules densify;
    bool white_background = false;      // the reference resets opacity at densify_from too
};

// What the reference schedule does around step `iteration` (counted from 1): the SH degree the step
// evaluates, then whether it densifies (and with prune_large) and resets opacity after it.
struct ScheduledStep {
    int sh_degree = 0;
    bool densify = false, prune_large = false, reset_opacity = false;
};
ScheduledStep scheduled_step(const ReferenceSchedule& schedule, uint64_t iteration);

// The reference schedule, and where asked for, a settling after its densification window.
class ReferenceStrategy final : public Strategy {
public:
    explicit ReferenceStrategy(const ReferenceSchedule& schedule, std::optional<Settling> settling = {})
        : schedule_(schedule), settling_(std::move(settling)) {}
    void before_step(Trainer& trainer, uint64_t iteration) override;
    void after_step(Trainer& trainer, uint64_t iteration) override;
    const ImportancePrunes& events() const { return events_; }

private:
    ReferenceSchedule schedule_;
    std::optional<Settling> settling_;
    ImportancePrunes events_;
};

}  // namespace vksplat::train
