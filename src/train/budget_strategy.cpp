#include "vksplat/train/budget_strategy.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vksplat::train {

size_t peak_count(const BudgetSchedule& budget) {
    const double grown = double(budget.budget) * std::max(1.0, budget.peak);
    return std::max(budget.budget, std::min(size_t(std::llround(grown)), budget.peak_limit));
}

size_t growth_target(const ReferenceSchedule& reference, const BudgetSchedule& budget, uint64_t iteration) {
    if (budget.budget <= budget.start) return budget.budget;
    const size_t peak = peak_count(budget);
    const double from = double(reference.densify_from);
    const double span = budget.reach * (double(reference.densify_until) - from);
    const double p = span > 0 ? std::clamp((double(iteration) - from) / span, 0.0, 1.0) : 1.0;
    const double grown = 1.0 - std::pow(1.0 - p, budget.growth_exponent);
    return budget.start + size_t(std::llround(double(peak - budget.start) * grown));
}

BudgetStrategy::BudgetStrategy(const ReferenceSchedule& reference, const BudgetSchedule& budget, Importance importance)
    : reference_(reference), budget_(budget), importance_(std::move(importance)),
      settling_(budget.settle, {.budget = budget.budget}, importance_) {
    if (budget_.budget == 0) throw std::invalid_argument("BudgetStrategy: a budget of 0 Gaussians");
    if (!(budget_.growth_exponent > 0) || !(budget_.reach > 0 && budget_.reach <= 1))
        throw std::invalid_argument("BudgetStrategy: growth exponent must be > 0 and reach in (0, 1]");
    if (!(budget_.prune_ratio >= 0 && budget_.prune_ratio < 1))
        throw std::invalid_argument("BudgetStrategy: prune ratio must lie in [0, 1)");
    if (!(budget_.peak >= 1))
        throw std::invalid_argument("BudgetStrategy: the peak must be at least the budget");
    if ((budget_.prune_ratio > 0 || peak_count(budget_) > budget_.budget) && !importance_)
        throw std::invalid_argument("BudgetStrategy: pruning needs an importance function");
}

void BudgetStrategy::before_step(Trainer& trainer, uint64_t iteration) {
    trainer.set_sh_degree(scheduled_step(reference_, iteration).sh_degree);
    settling_.before_step(trainer, iteration);
}

void BudgetStrategy::after_step(Trainer& trainer, uint64_t iteration) {
    const ScheduledStep step = scheduled_step(reference_, iteration);
    // Scored before this step densifies, on Gaussians that have trained since the last reset
    // (right after one, every opacity is 0.01 and blend weights say little); Trainer::remove keeps
    // the densification sums, so the densification below still sees all of them.
    if (step.densify && step.reset_opacity && budget_.prune_ratio > 0) {
        const size_t keep = size_t(std::llround(double(trainer.size()) * (1.0 - budget_.prune_ratio)));
        remove_least_important(trainer, importance_, events_, [keep](const std::vector<float>&) { return keep; });
    }
    if (step.densify) {
        DensifyRules rules = reference_.densify;
        rules.prune_large = step.prune_large && budget_.prune_large;
        rules.grad_threshold = budget_.min_gradient;
        rules.ranking = budget_.ranking;
        rules.max_gaussians = std::max<size_t>(1, growth_target(reference_, budget_, iteration));
        trainer.densify(rules);
    }
    if (step.reset_opacity && budget_.reset_opacity) trainer.reset_opacity(reference_.opacity_reset_value);
    settling_.after_step(trainer, iteration, events_);
}

}  // namespace vksplat::train
