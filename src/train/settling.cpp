#include "vksplat/train/settling.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace vksplat::train {

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

size_t count_carrying(const std::vector<float>& importance, double share) {
    if (!(share > 0 && share <= 1)) throw std::invalid_argument("count_carrying: the share must lie in (0, 1]");
    std::vector<double> values(importance.size());
    std::transform(importance.begin(), importance.end(), values.begin(),
                   [](float v) { return std::isfinite(v) && v > 0 ? double(v) : 0.0; });
    std::sort(values.begin(), values.end(), std::greater<>());
    const double total = std::accumulate(values.begin(), values.end(), 0.0);
    double carried = 0;
    size_t count = 0;
    while (count < values.size() && (count == 0 || carried < share * total)) carried += values[count++];
    return std::max<size_t>(count, 1);
}

size_t settle_target(size_t count, size_t budget, int rounds_left) {
    if (count <= budget || rounds_left <= 1) return std::min(count, budget);
    const double share = double(rounds_left - 1) / double(rounds_left);
    return std::max(budget, size_t(std::llround(double(budget) * std::pow(double(count) / double(budget), share))));
}

void remove_least_important(Trainer& trainer, const Importance& importance, ImportancePrunes& events,
                            const std::function<size_t(const std::vector<float>&)>& keep) {
    if (!importance) throw std::logic_error("settling: no importance function to rank by");
    const auto start = std::chrono::steady_clock::now();
    // The importance renders the training views with a renderer of its own, and the removal that
    // follows frees the trainer's frame anyway: freed first, the two frames are never held at once.
    trainer.release_frame();
    const std::vector<float> scores = importance(trainer.cloud());
    events.importance_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (scores.size() != trainer.size()) throw std::logic_error("settling: the importance function scored another scene");
    events.pruned += trainer.remove(keep_most_important(scores, keep(scores)));
    ++events.prune_events;
}

Settling::Settling(SettleSchedule schedule, SettleTarget target, Importance importance)
    : schedule_(schedule), target_(target), importance_(std::move(importance)) {
    if (schedule_.rounds < 1 || (schedule_.rounds > 1 && schedule_.spacing == 0))
        throw std::invalid_argument("settling: at least one round, rounds apart");
    if (target_.share != 0 && !(target_.share > 0 && target_.share <= 1))
        throw std::invalid_argument("settling: the share of the importance kept must lie in (0, 1]");
    if (target_.budget == 0 && target_.share == 0) throw std::invalid_argument("settling: neither a budget nor a share");
    // Every round inside the run: a short run settles in rounds closer together, or at once.
    const uint64_t after = schedule_.iterations > schedule_.at ? schedule_.iterations - schedule_.at : 0;
    schedule_.spacing = std::min(schedule_.spacing, after / uint64_t(schedule_.rounds));
    if (schedule_.spacing == 0) schedule_.rounds = 1;
}

void Settling::before_step(Trainer& trainer, uint64_t iteration) const {
    // Set on every step after the first round, not once, so that a resumed run has it.
    if (schedule_.restart_decay && iteration > schedule_.at && schedule_.iterations > schedule_.at) {
        const uint64_t steps = schedule_.iterations - schedule_.at;
        trainer.set_position_decay(schedule_.at, int(std::min<uint64_t>(steps, std::numeric_limits<int>::max())));
    }
}

void Settling::after_step(Trainer& trainer, uint64_t iteration, ImportancePrunes& events) const {
    const uint64_t spacing = std::max<uint64_t>(schedule_.spacing, 1);
    if (iteration < schedule_.at || (iteration - schedule_.at) % spacing != 0) return;
    const uint64_t round = (iteration - schedule_.at) / spacing;
    if (round >= uint64_t(schedule_.rounds)) return;
    const int rounds_left = schedule_.rounds - int(round);
    if (target_.share == 0 && trainer.size() <= target_.budget) return;
    remove_least_important(trainer, importance_, events, [&](const std::vector<float>& scores) {
        const size_t budget = target_.share > 0 ? count_carrying(scores, target_.share) : target_.budget;
        return settle_target(scores.size(), budget, rounds_left);
    });
}

}  // namespace vksplat::train
