#pragma once
// Importance scores: one number per Gaussian, higher = more worth keeping. Selection
// (selection.hpp) drops the lowest.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vksplat/prune/accumulate.hpp"
#include "vksplat/scene/scene.hpp"

namespace vksplat::prune {

enum class ScoreMethod {
    opacity,       // sigmoid of the stored logit
    footprint,     // sum over views of opacity * pi * r^2, r the projected radius in pixels
    blend,         // sum over every pixel of every view of alpha * T
    blend_max,     // max over pixels and views of alpha * T
    blend_mix,     // sqrt(blend * blend_max): what a Gaussian adds overall and where it matters most
    volume_blend,  // blend * (V / V90)^0.1, V the product of the three scales (LightGaussian)
    random,        // seeded uniform in [0, 1): the baseline the others must beat
    fisher,        // log det of the Fisher information of the pictures in mean and log-scale (PUP 3D-GS, fisher.hpp)
};

// "opacity", "footprint", "blend", "blend-max", "blend-mix", "volume-blend", "random", "fisher".
std::string_view to_string(ScoreMethod method);
// Every method's name, in the order of the enum.
std::vector<std::string> score_method_names();
// The method named `name`; throws InputError listing the names for anything else.
ScoreMethod parse_score_method(std::string_view name);
// Whether the method reads the view totals (opacity and random need no rendering).
bool uses_views(ScoreMethod method);
// Whether the method reads ViewTotals::fisher, which accumulate() gathers only when asked.
bool needs_fisher(ScoreMethod method);

// sigmoid(logit) per Gaussian.
std::vector<float> opacities(const GaussianCloud& cloud);

// The scores of `method` for each Gaussian of `cloud`. `totals` must be the cloud's (same size)
// for the methods that use views, and is ignored by the others; `seed` is read only by random,
// whose scores are the same for a seed on every platform. Expects a sanitised cloud (finite scales).
// Throws std::invalid_argument when the totals do not match the cloud, InputError for fisher from
// totals without it (such as a file of five columns).
std::vector<float> score(const GaussianCloud& cloud, const ViewTotals& totals, ScoreMethod method,
                         uint64_t seed = 0);

// The weights a sampled selection draws by (selection.hpp's sampling_keys): the scores themselves,
// which are sums of contributions, but for fisher, whose score is a logarithm (log det F, negative
// for many a Gaussian that matters): det(F)^(1/6), the geometric mean of F's eigenvalues (a
// sensitivity per parameter), divided by the largest (the sample depends on ratios only).
std::vector<float> sampling_weights(std::span<const float> scores, ScoreMethod method);

// np.percentile(values, percent) with its default (linear) interpolation; 0 for no values.
double percentile(std::vector<double> values, double percent);

}  // namespace vksplat::prune
