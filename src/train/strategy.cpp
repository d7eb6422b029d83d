#include "vksplat/train/strategy.hpp"

#include <algorithm>

namespace vksplat::train {

ScheduledStep scheduled_step(const ReferenceSchedule& s, uint64_t iteration) {
    ScheduledStep step;
    step.sh_degree = int(std::min<uint64_t>(uint64_t(s.sh_degree), iteration / s.sh_degree_interval));
    if (iteration >= s.densify_until) return step;
    step.densify = iteration > s.densify_from && iteration % s.densify_interval == 0;
    step.prune_large = step.densify && iteration > s.opacity_reset_interval;
    step.reset_opacity = iteration % s.opacity_reset_interval == 0 || (s.white_background && iteration == s.densify_from);
    return step;
}

void ReferenceStrategy::before_step(Trainer& trainer, uint64_t iteration) {
    trainer.set_sh_degree(scheduled_step(schedule_, iteration).sh_degree);
    if (settling_) settling_->before_step(trainer, iteration);
}

void ReferenceStrategy::after_step(Trainer& trainer, uint64_t iteration) {
    const ScheduledStep step = scheduled_step(schedule_, iteration);
    if (step.densify) {
        DensifyRules rules = schedule_.densify;
        rules.prune_large = step.prune_large;
        trainer.densify(rules);
    }
    if (step.reset_opacity) trainer.reset_opacity(schedule_.opacity_reset_value);
    if (settling_) settling_->after_step(trainer, iteration, events_);
}

}  // namespace vksplat::train
