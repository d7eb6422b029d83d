#include "train/relocation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "train/parameter_layout.hpp"

namespace vksplat::train {
namespace {

constexpr int kMostCopies = 51;

double sigmoid(double x) { return 1.0 / (1.0 + std::exp(-x)); }

}  // namespace

RelocatedCopy relocated_copy(double opacity, int copies) {
    const int n = std::clamp(copies, 1, kMostCopies);
    RelocatedCopy copy;
    copy.opacity = 1.0 - std::pow(1.0 - opacity, 1.0 / n);
    // The paper's double sum, sum over i = 1..n, k = 0..i-1 of C(i-1, k) (-1)^k o'^(k+1) / sqrt(k+1),
    // is (summing C(i-1, k) over i) the single sum of C(n, m) (-1)^(m+1) o'^m / sqrt(m), m = 1..n:
    // the composite's integrated profile per unit of scale.
    double sum = 0, binomial = 1, power = 1;
    for (int m = 1; m <= n; ++m) {
        binomial *= double(n - m + 1) / m;
        power *= copy.opacity;
        sum += (m % 2 ? 1.0 : -1.0) * binomial * power / std::sqrt(double(m));
    }
    copy.scale_factor = sum > 0 ? opacity / sum : 1.0;
    return copy;
}

RelocationPlan plan_relocation(const DensifyInputs& inputs, const RelocationRules& rules, uint64_t seed) {
    const size_t n = inputs.count;
    if (inputs.geometry.size() != 11 * n) throw std::invalid_argument("plan_relocation: inputs of the wrong size");
    const ParameterLayout layout{inputs.count, 1};
    RelocationPlan result;
    result.report.before = n;

    // The scene as it will be: slot i copies old Gaussian source[i], with these opacities and
    // log-scales; `own` marks the slots whose values differ from their source's.
    std::vector<uint32_t> source(n);
    std::vector<double> opacity(n);
    std::vector<float> log_scale(3 * n);
    std::vector<uint8_t> own(n, 0);
    std::vector<uint32_t> dead;
    std::vector<double> weight(n);
    for (uint32_t i = 0; i < n; ++i) {
        source[i] = i;
        opacity[i] = sigmoid(inputs.geometry[layout.opacities() + i]);
        for (int k = 0; k < 3; ++k) log_scale[3 * i + k] = inputs.geometry[layout.log_scales() + 3 * i + k];
        const bool is_dead = !(opacity[i] > rules.min_opacity);  // NaN counts as dead
        if (is_dead) dead.push_back(i);
        weight[i] = is_dead ? 0.0 : opacity[i];
    }
    // Nothing alive to draw from: every Gaussian stays as it is.
    if (dead.size() == n) {
        result.plan.sources = source;
        result.plan.fresh_from = result.plan.override_from = uint32_t(n);
        result.report.after = n;
        return result;
    }
    std::mt19937_64 rng(seed);
    // Draws `count` slots with probability proportional to weight; each drawn slot takes its
    // share of its place (relocated_copy), and the draws come back in order.
    const auto draw = [&](size_t count) {
        std::discrete_distribution<uint32_t> pick(weight.begin(), weight.end());
        std::vector<uint32_t> drawn(count);
        std::vector<int> times(source.size(), 0);
        for (auto& d : drawn) ++times[d = pick(rng)];
        for (uint32_t i = 0; i < times.size(); ++i) {
            if (times[i] == 0) continue;
            const RelocatedCopy copy = relocated_copy(opacity[i], times[i] + 1);
            // As the paper clamps: never below the threshold that would make it dead at once.
            opacity[i] = std::clamp(copy.opacity, rules.min_opacity, 1.0 - std::numeric_limits<float>::epsilon());
            for (int k = 0; k < 3; ++k) log_scale[3 * i + k] += float(std::log(copy.scale_factor));
            own[i] = 1;
        }
        return drawn;
    };
    const auto copy_slot = [&](uint32_t to, uint32_t from) {
        source[to] = source[from];
        opacity[to] = opacity[from];
        for (int k = 0; k < 3; ++k) log_scale[3 * to + k] = log_scale[3 * from + k];
        own[to] = 1;
    };
    // The transparent move onto the drawn, then the scene grows by copies of the drawn.
    const std::vector<uint32_t> onto = draw(dead.size());
    for (size_t k = 0; k < dead.size(); ++k) copy_slot(dead[k], onto[k]);
    result.report.relocated = dead.size();
    for (uint32_t i = 0; i < n; ++i) weight[i] = opacity[i];
    const size_t added = rules.target > n ? rules.target - n : 0;
    for (uint32_t from : draw(added)) {
        source.push_back(0);
        opacity.push_back(0);
        log_scale.insert(log_scale.end(), 3, 0.0f);
        own.push_back(0);
        copy_slot(uint32_t(source.size() - 1), from);
    }
    result.report.added = added;

    DensifyPlan& plan = result.plan;
    for (size_t j = 0; j < source.size(); ++j)
        if (!own[j]) plan.sources.push_back(source[j]);
    plan.fresh_from = plan.override_from = uint32_t(plan.sources.size());
    for (size_t j = 0; j < source.size(); ++j) {
        if (!own[j]) continue;
        const uint32_t i = source[j];
        const float* p = &inputs.geometry[layout.positions() + 3 * i];
        plan.add_override(i, {p[0], p[1], p[2]}, {log_scale[3 * j], log_scale[3 * j + 1], log_scale[3 * j + 2]},
                          float(std::log(opacity[j] / (1.0 - opacity[j]))));
    }
    plan.report = {.before = n, .after = plan.sources.size()};
    result.report.after = plan.sources.size();
    return result;
}

}  // namespace vksplat::train
