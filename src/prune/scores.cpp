// The importance scores, each from the cloud itself or from the totals over the training views.
#include "vksplat/prune/scores.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <stdexcept>

#include "vksplat/error.hpp"

namespace vksplat::prune {
namespace {

struct MethodName {
    ScoreMethod method;
    std::string_view name;
};
constexpr std::array<MethodName, 8> kMethods = {{
    {ScoreMethod::opacity, "opacity"},
    {ScoreMethod::footprint, "footprint"},
    {ScoreMethod::blend, "blend"},
    {ScoreMethod::blend_max, "blend-max"},
    {ScoreMethod::blend_mix, "blend-mix"},
    {ScoreMethod::volume_blend, "volume-blend"},
    {ScoreMethod::random, "random"},
    {ScoreMethod::fisher, "fisher"},
}};

// LightGaussian's exponent on the normalised volume: large Gaussians gain a little, so that a big
// faint splat that covers much of the picture is not ranked below a tiny opaque one.
constexpr double kVolumePower = 0.1;

template <typename T>
std::vector<float> as_float(const std::vector<T>& values) {
    return std::vector<float>(values.begin(), values.end());
}

std::vector<float> volume_blend(const GaussianCloud& cloud, const ViewTotals& totals) {
    std::vector<double> volume(cloud.size());
    for (size_t i = 0; i < cloud.size(); ++i)
        volume[i] = std::exp(double(cloud.log_scales[3 * i]) + cloud.log_scales[3 * i + 1] + cloud.log_scales[3 * i + 2]);
    // The normalisation scales every score alike, so it changes no ranking, only what a threshold
    // means. (LightGaussian's code reads index 0.9 N of a descending sort, its 10th percentile; we
    // follow the paper's text, the 90th.)
    const double v90 = percentile(volume, 90.0);
    std::vector<float> scores(cloud.size());
    for (size_t i = 0; i < cloud.size(); ++i)
        scores[i] = float(totals.blend[i] * std::pow(volume[i] / v90, kVolumePower));
    return scores;
}

// 24 random bits per Gaussian from std::mt19937_64's raw output, which the standard fixes (the
// std:: distributions are not portable), as a float in [0, 1).
std::vector<float> random_scores(size_t n, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::vector<float> scores(n);
    for (float& s : scores) s = float(rng() >> 40) * (1.0f / 16777216.0f);
    return scores;
}

}  // namespace

std::string_view to_string(ScoreMethod method) {
    for (const auto& m : kMethods)
        if (m.method == method) return m.name;
    throw std::invalid_argument("prune::to_string: unknown ScoreMethod");
}

std::vector<std::string> score_method_names() {
    std::vector<std::string> names;
    for (const auto& m : kMethods) names.emplace_back(m.name);
    return names;
}

ScoreMethod parse_score_method(std::string_view name) {
    for (const auto& m : kMethods)
        if (m.name == name) return m.method;
    std::string known;
    for (const auto& m : kMethods) known += (known.empty() ? "" : ", ") + std::string(m.name);
    throw InputError("score method '" + std::string(name) + "'", "unknown (use one of " + known + ")");
}

bool uses_views(ScoreMethod method) { return method != ScoreMethod::opacity && method != ScoreMethod::random; }

bool needs_fisher(ScoreMethod method) { return method == ScoreMethod::fisher; }

std::vector<float> opacities(const GaussianCloud& cloud) {
    std::vector<float> opacity(cloud.size());
    for (size_t i = 0; i < cloud.size(); ++i) opacity[i] = float(1.0 / (1.0 + std::exp(-double(cloud.opacity_logits[i]))));
    return opacity;
}

std::vector<float> score(const GaussianCloud& cloud, const ViewTotals& totals, ScoreMethod method, uint64_t seed) {
    if (uses_views(method) && totals.size() != cloud.size())
        throw std::invalid_argument("prune::score: totals for " + std::to_string(totals.size()) +
                                    " Gaussians, the cloud has " + std::to_string(cloud.size()));
    switch (method) {
        case ScoreMethod::opacity: return opacities(cloud);
        case ScoreMethod::footprint: return as_float(totals.footprint);
        case ScoreMethod::blend: return as_float(totals.blend);
        case ScoreMethod::blend_max: return totals.blend_max;
        case ScoreMethod::blend_mix: {
            std::vector<float> scores(cloud.size());
            for (size_t i = 0; i < cloud.size(); ++i) scores[i] = float(std::sqrt(totals.blend[i] * totals.blend_max[i]));
            return scores;
        }
        case ScoreMethod::volume_blend: return volume_blend(cloud, totals);
        case ScoreMethod::random: return random_scores(cloud.size(), seed);
        case ScoreMethod::fisher:
            if (totals.fisher.empty())
                throw InputError("--method fisher", "the view totals hold no Fisher scores (they are gathered for this "
                                                    "method only; a totals file of five columns has none)");
            return totals.fisher;
    }
    throw std::invalid_argument("prune::score: unknown ScoreMethod");
}

std::vector<float> sampling_weights(std::span<const float> scores, ScoreMethod method) {
    std::vector<float> weights(scores.begin(), scores.end());
    if (method != ScoreMethod::fisher || weights.empty()) return weights;
    const float largest = *std::max_element(weights.begin(), weights.end());
    for (float& w : weights) w = float(std::exp((double(w) - double(largest)) / 6.0));
    return weights;
}

double percentile(std::vector<double> values, double percent) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const double rank = percent / 100.0 * double(values.size() - 1);
    const size_t below = std::min(size_t(rank), values.size() - 1);
    const size_t above = std::min(below + 1, values.size() - 1);
    return values[below] + (rank - double(below)) * (values[above] - values[below]);
}

}  // namespace vksplat::prune
