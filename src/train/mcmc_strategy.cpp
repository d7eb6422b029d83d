#include "vksplat/train/mcmc_strategy.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vksplat::train {

void use_mcmc_terms(const McmcSchedule& schedule, TrainOptions& options) {
    options.opacity_regularization = schedule.opacity_regularization;
    options.scale_regularization = schedule.scale_regularization;
    options.position_noise = schedule.position_noise;
}

McmcStrategy::McmcStrategy(const ReferenceSchedule& reference, const McmcSchedule& schedule)
    : reference_(reference), schedule_(schedule) {
    if (schedule_.budget == 0) throw std::invalid_argument("McmcStrategy: a budget of 0 Gaussians");
    if (!(schedule_.growth >= 1)) throw std::invalid_argument("McmcStrategy: growth must be at least 1");
    if (schedule_.refine_every == 0) throw std::invalid_argument("McmcStrategy: refine_every must be > 0");
}

void McmcStrategy::before_step(Trainer& trainer, uint64_t iteration) {
    trainer.set_sh_degree(scheduled_step(reference_, iteration).sh_degree);
}

void McmcStrategy::after_step(Trainer& trainer, uint64_t iteration) {
    if (iteration <= schedule_.refine_from || iteration >= schedule_.refine_until ||
        iteration % schedule_.refine_every != 0)
        return;
    const auto grown = size_t(std::floor(double(trainer.size()) * schedule_.growth));
    const RelocationReport report =
        trainer.relocate({.min_opacity = schedule_.min_opacity, .target = std::min(schedule_.budget, grown)});
    events_.relocated += report.relocated;
    events_.added += report.added;
}

}  // namespace vksplat::train
