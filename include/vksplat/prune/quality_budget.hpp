#pragma once
// The smallest model that stays within a quality budget: a bisection on the number of Gaussians
// kept (best first, as a Ranking orders them), each probe rendering the test views.
//
// The drop a probe is judged by:
//   - against photos: the unpruned scene's mean PSNR minus the probe's (both over the test views);
//   - against renders of the unpruned scene: there the unpruned scene scores +infinity, so the drop
//     is estimated instead. If the unpruned scene's own error against its (absent) photos has MSE
//     m0 = 10^(-P/10), P = assumed_psnr, and pruning adds an error of MSE d uncorrelated with it,
//     the photos would show a drop of 10 log10(1 + d / m0) dB. That is taken per view and averaged.
//     With P = 30 dB a 0.1 dB budget asks for about 46 dB against the unpruned render.
// The bisection assumes that keeping more never raises the drop; it finds a count K whose probe met
// the budget and, unless K is 0, whose neighbour K - 1 was probed and missed it.
#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "vksplat/eval/quality.hpp"
#include "vksplat/prune/selection.hpp"
#include "vksplat/prune/sh_precision.hpp"

namespace vksplat::prune {

struct QualityBudget {
    double max_psnr_drop = 0.1;      // dB
    // Also try SH degrees below the scene's at the count found, and keep the lowest that still
    // meets the budget (trying downwards, stopping at the first that misses).
    bool allow_sh_reduction = false;
    double assumed_psnr = 30.0;      // dB, used only without photos (see above)
    // When set, each probe's model passes through it before it is measured (prune --recover
    // re-fits it to the photos), so the budget holds for the re-fitted model.
    std::function<GaussianCloud(const GaussianCloud&)> refit;
};

struct BudgetProbe {
    size_t kept = 0;
    int sh_degree = 0;
    double sh_share = 0;  // of the higher bands, dropped per Gaussian (prune/sh_reduction.hpp)
    ShPrecision sh_precision;  // of the higher bands' values (prune/sh_precision.hpp)
    size_t bytes = 0;     // the model's file, where a size budget measured it; else 0
    double psnr = 0;      // mean over the test views against the targets
    double drop = 0;      // dB, as defined above
    double seconds = 0;   // wall time of the probe: subset, upload, renders, metrics
    bool meets = false;
    bool refitted = false;  // measured after SizeBudget::refit (a shortlisted size candidate)
};

struct BudgetResult {
    KeepMask keep;
    size_t kept = 0;
    int sh_degree = 0;
    double sh_share = 0;       // of the higher bands, dropped per Gaussian (a size budget's choice)
    ShPrecision sh_precision;  // of the higher bands' values (a size budget's choice)
    double baseline_psnr = 0;  // `cloud`'s mean PSNR against the photos; 0 without photos
    double psnr = 0, drop = 0; // of the model chosen
    // False when even every candidate (all the lossless pass left) misses the budget; the result
    // is then that model.
    bool met = false;
    std::vector<BudgetProbe> probes;
    // With QualityBudget::refit: the chosen probe's re-fitted model (re-fitting again would not
    // give it back exactly: float atomics sum gradients in varying order). From a size budget: the
    // model chosen, SH bands dropped per Gaussian included.
    std::optional<GaussianCloud> model;
};

// The drop of a model measured as `quality` on `views`, as defined above (`baseline_psnr` is the
// unpruned scene's mean PSNR against photos; unused against renders).
double psnr_drop(const eval::Quality& quality, const eval::TestViews& views, double baseline_psnr,
                 double assumed_psnr);

// `cloud` is the unpruned scene, `ranking` orders its candidates (see selection.hpp). Probes are
// made of cloud.subset(ranking.keep_best(K)) at the cloud's SH degree (and lower ones, when
// allowed); `on_probe` hears of each as it finishes. Throws InputError for a negative or NaN budget.
BudgetResult fit_quality_budget(Renderer& renderer, const GaussianCloud& cloud, const Ranking& ranking,
                                const eval::TestViews& views, const QualityBudget& budget,
                                const RenderSettings& settings,
                                const std::function<void(const BudgetProbe&)>& on_probe = {});

}  // namespace vksplat::prune
