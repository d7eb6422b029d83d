#include "vksplat/train/budget_strategy.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace vksplat::train {

size_t growth_target(const ReferenceSchedule& reference, const BudgetSchedule& budget, uint64_t iteration) {
    if (budget.budget <= budget.start) return budget.budget;
    const size_t peak = size_t(std::llround(double(budget.budget) * std::max(1.0, budget.peak)));
    const double from = double(reference.densify_from);
    const double span = budget.reach * (double(reference.densify_until) - from);
    const double p = span > 0 ? std::clamp((double(iteration) - from) / span, 0.0, 1.0) : 1.0;
    const double grown = 1.0 - std::pow(1.0 - p, budget.growth_exponent);
    return budget.start + size_t(std::llround(double(peak - budget.start) * grown));
}

size_t settle_target(size_t count, size_t budget, int rounds_left) {
    if (count <= budget || rounds_left <= 1) return std::min(count, budget);
    const double share = double(rounds_left - 1) / double(rounds_left);
    return std::max(budget, size_t(std::llround(double(budget) * std::pow(double(count) / double(budget), share))));
}

std::vector<uint8_t> keep_most_important(const std::vector<float>& importance, size_t count) {
    const size_t n = importance.size();
    // The last Gaussian stays: an empty scene cannot train on.
    const size_t drop = n - std::clamp<size_t>(count, std::min<size_t>(n, 1), n);
    std::vector<uint32_t> order(n);
    std::iota(order.begin(), order.end(), 0u);
    // NaN ranks lowest: a score that is not a number is no reason to keep a Gaussian.
    const auto key = [&](uint32_t i) { return std::isnan(importance[i]) ? -INFINITY : importance[i]; };
    std::nth_element(order.begin(), order.begin() + long(drop), order.end(), [&](uint32_t a, uint32_t b) {
        return key(a) < key(b) || (key(a) == key(b) && a < b);
    });
    std::vector<uint8_t> keep(n, 1);
    for (size_t k = 0; k < drop; ++k) keep[order[k]] = 0;
    return keep;
}

BudgetStrategy::BudgetStrategy(const ReferenceSchedule& reference, const BudgetSchedule& budget, Importance importance)
    : reference_(reference), budget_(budget), importance_(std::move(importance)) {
    if (budget_.budget == 0) throw std::invalid_argument("BudgetStrategy: a budget of 0 Gaussians");
    if (!(budget_.growth_exponent > 0) || !(budget_.reach > 0 && budget_.reach <= 1))
        throw std::invalid_argument("BudgetStrategy: growth exponent must be > 0 and reach in (0, 1]");
    if (!(budget_.prune_ratio >= 0 && budget_.prune_ratio < 1))
        throw std::invalid_argument("BudgetStrategy: prune ratio must lie in [0, 1)");
    if (budget_.settle_rounds < 1 || (budget_.settle_rounds > 1 && budget_.settle_spacing == 0))
        throw std::invalid_argument("BudgetStrategy: at least one settling round, rounds apart");
    // Every settling round inside the run: a short run settles in rounds closer together, or at once.
    const uint64_t after = budget_.iterations > budget_.settle_at ? budget_.iterations - budget_.settle_at : 0;
    budget_.settle_spacing = std::min(budget_.settle_spacing, after / uint64_t(budget_.settle_rounds));
    if (budget_.settle_spacing == 0) budget_.settle_rounds = 1;
    if (!(budget_.peak >= 1))
        throw std::invalid_argument("BudgetStrategy: the peak must be at least the budget");
    if ((budget_.prune_ratio > 0 || budget_.peak > 1) && !importance_)
        throw std::invalid_argument("BudgetStrategy: pruning needs an importance function");
}

void BudgetStrategy::prune_to(Trainer& trainer, size_t count) {
    const auto start = std::chrono::steady_clock::now();
    const std::vector<float> importance = importance_(trainer.cloud());
    events_.importance_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (importance.size() != trainer.size())
        throw std::logic_error("BudgetStrategy: the importance function scored another scene");
    events_.pruned += trainer.remove(keep_most_important(importance, count));
    ++events_.prune_events;
}

void BudgetStrategy::before_step(Trainer& trainer, uint64_t iteration) {
    trainer.set_sh_degree(scheduled_step(reference_, iteration).sh_degree);
    // Set on every step after the settling, not once, so that a run resumed from a checkpoint has it.
    if (budget_.restart_decay && iteration > budget_.settle_at && budget_.iterations > budget_.settle_at) {
        const uint64_t steps = budget_.iterations - budget_.settle_at;
        trainer.set_position_decay(budget_.settle_at, int(std::min<uint64_t>(steps, std::numeric_limits<int>::max())));
    }
}

void BudgetStrategy::after_step(Trainer& trainer, uint64_t iteration) {
    const ScheduledStep step = scheduled_step(reference_, iteration);
    // Scored before this step densifies, on Gaussians that have trained since the last reset
    // (right after one, every opacity is 0.01 and blend weights say little); Trainer::remove keeps
    // the densification sums, so the densification below still sees all of them.
    if (step.densify && step.reset_opacity && budget_.prune_ratio > 0)
        prune_to(trainer, size_t(std::llround(double(trainer.size()) * (1.0 - budget_.prune_ratio))));
    if (step.densify) {
        DensifyRules rules = reference_.densify;
        rules.prune_large = step.prune_large && budget_.prune_large;
        rules.grad_threshold = budget_.min_gradient;
        rules.ranking = budget_.ranking;
        rules.max_gaussians = std::max<size_t>(1, growth_target(reference_, budget_, iteration));
        trainer.densify(rules);
    }
    if (step.reset_opacity && budget_.reset_opacity) trainer.reset_opacity(reference_.opacity_reset_value);
    const uint64_t spacing = std::max<uint64_t>(budget_.settle_spacing, 1);
    if (iteration >= budget_.settle_at && (iteration - budget_.settle_at) % spacing == 0) {
        const uint64_t round = (iteration - budget_.settle_at) / spacing;
        if (round < uint64_t(budget_.settle_rounds) && trainer.size() > budget_.budget)
            prune_to(trainer, settle_target(trainer.size(), budget_.budget, budget_.settle_rounds - int(round)));
    }
}

}  // namespace vksplat::train
