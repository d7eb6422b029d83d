#pragma once
// The best model that fits in a number of bytes as a file of a given format: Gaussian count traded
// against SH bands by measurement.
//
// The SH choices tried: every Gaussian at the cloud's degree D with a share s of its higher bands
// dropped per Gaussian (s = 0, 1/2D, 2/2D, ..., 1; prune/sh_reduction.hpp, among the Gaussians
// kept), and the whole cloud at each degree between 1 and D - 1; each at every SH precision of the
// budget (below). Dropping bands per Gaussian only shrinks a file whose format compresses zeros
// (SPZ); a choice whose file of the best 8,192 candidates is no smaller than that of the
// unreduced one is skipped unmeasured, as it can only keep fewer Gaussians and less colour. For
// every other choice, a search on the count kept (best first, as a Ranking orders them;
// largest_fitting) finds the most Gaussians whose file fits, each probe writing the file (the
// choices' searches run on all cores at once); each choice's model is then rendered on the test
// views, and the one of least PSNR drop (as quality_budget.hpp defines it) is kept. When every
// candidate at full SH fits, that is the model.
#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <string>

#include "vksplat/prune/quality_budget.hpp"
#include "vksplat/prune/sh_precision.hpp"

namespace vksplat::prune {

struct SizeBudget {
    size_t max_bytes = 0;
    std::string format;          // as io::write_scene names it ("spz", "compressed-ply", ...)
    double assumed_psnr = 30.0;  // dB, used only without photos (see quality_budget.hpp)
    // The candidates' SH rounded to this precision (sh_precision.hpp) before their bytes and
    // quality are measured; unset: each of kSizeBudgetPrecisions is tried, as another choice.
    std::optional<ShPrecision> sh_precision;
    // With a re-fit to come (prune --recover): a shortlist of the candidates passes through it
    // before each is measured again, and the one of least drop after it is chosen. The shortlist:
    // at each precision, the candidate of least drop as it is and the one with every band at the
    // cloud's degree. A re-fit makes up for lost Gaussians far better than for lost bands or bits
    // (bonsai at 3 MB, H200: the choice by drop before re-fitting, 152,532 Gaussians with 83% of
    // the higher bands dropped at 5,4 bits, re-fitted to -1.459 dB; 81% dropped with every band at
    // 6,6 bits to -0.255), so the candidates as they are rank the wrong way round. A re-fitted
    // candidate's file grows (its values compress less well): its count becomes the one whose file,
    // grown as much, fits, so that the rounds re-fit what will be written.
    std::function<GaussianCloud(const GaussianCloud&)> refit;
};

// The SH precisions a size budget tries when none is set: full, 6 bits (bonsai's SPZ 0.74x for
// -0.09 dB) and SPZ's encoder's 5 and 4 (0.55x for -1.24 dB). A precision whose file at full SH
// and count is no smaller than at full precision (formats that do not entropy-code the SH bytes)
// is skipped unmeasured.
inline constexpr ShPrecision kSizeBudgetPrecisions[] = {{8, 8}, {6, 6}, {5, 4}};

// The bytes `cloud` takes as a file of `format`, written to a temporary file that is then removed.
size_t scene_file_bytes(const GaussianCloud& cloud, const std::string& format);

// The largest count in [1, most] whose `bytes_of(count)` is at most `max_bytes` (bytes_of must not
// fall as the count grows); 0 when not even a count of 1 fits, or most is 0. The search interpolates
// between the counts it has tried, since files grow nearly in proportion to their Gaussians, and
// halves where that does not close in: about 5 calls for a near-linear file where bisection took
// 20, at worst three for each halving. It asks for `most`, the costliest count, only where the
// line through the counts below says it may fit.
size_t largest_fitting(size_t most, size_t max_bytes, const std::function<size_t(size_t)>& bytes_of);

// Throws InputError, naming the smallest size reachable, unless `smallest` (the smallest model
// there can be: one Gaussian at SH degree 0, or an empty cloud) fits the budget as its format.
void check_size_reachable(const GaussianCloud& smallest, const SizeBudget& budget);

// The share of its model's higher bands (degrees 1 to BudgetResult::sh_degree) that a size
// budget's choice drops per Gaussian; 0 for a whole-degree choice. BudgetResult::sh_share counts
// the bands of the cloud's degree `cloud_degree`, and a share that took every Gaussian's top band
// made a model of lower degree, of whose fewer bands the same bands kept are a larger share.
double model_sh_share(const BudgetResult& choice, int cloud_degree);

// The model a size budget chose, after its re-fit: `refitted`, re-fitted at the chosen model's
// degree (the re-fit gives colour back to the bands the choice dropped, which the file would pay
// for), with `sh_share` (model_sh_share) of its higher bands dropped per Gaussian again,
// the cheapest by its own re-fitted coefficients and `weights` (its blend weights, one per
// Gaussian, or empty; sh_reduction.hpp), at the budget's SH precision (full where unset); then,
// if its file does not fit (re-fitted values compress less well), only as many of its best
// Gaussians by `scores` (one per Gaussian) as fit. Throws std::invalid_argument when the sizes
// differ.
GaussianCloud fit_refitted(const GaussianCloud& refitted, std::span<const double> weights, std::span<const float> scores,
                           double sh_share, const SizeBudget& budget);

// `cloud` is the unpruned scene, `ranking` orders its candidates, `weights` (empty, or one per
// Gaussian of `cloud`: prune::ViewTotals::blend) say what SH bands cost (sh_reduction.hpp). The
// result's model is the one chosen and `probes` hold each choice's measured model. Throws
// InputError when no model fits (check_size_reachable).
BudgetResult fit_size_budget(Renderer& renderer, const GaussianCloud& cloud, const Ranking& ranking,
                             std::span<const double> weights, const eval::TestViews& views, const SizeBudget& budget,
                             const RenderSettings& settings,
                             const std::function<void(const BudgetProbe&)>& on_probe = {});

}  // namespace vksplat::prune
