// Bisection on the kept count for the smallest model within a PSNR budget, then optionally fewer
// SH bands.
#include "vksplat/prune/quality_budget.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "vksplat/error.hpp"

namespace vksplat::prune {

double psnr_drop(const eval::Quality& quality, const eval::TestViews& views, double baseline_psnr, double assumed_psnr) {
    // Equal means (+infinity on both sides included, which a difference would make NaN) drop nothing.
    if (views.photos) return quality.mean_psnr == baseline_psnr ? 0.0 : baseline_psnr - quality.mean_psnr;
    // d / m0 = 10^((P - psnr) / 10) per view; an identical view (psnr = +inf) adds nothing.
    double sum = 0;
    for (double psnr : quality.psnr) sum += 10.0 * std::log10(1.0 + std::pow(10.0, (assumed_psnr - psnr) / 10.0));
    return quality.psnr.empty() ? 0.0 : sum / double(quality.psnr.size());
}

BudgetResult fit_quality_budget(Renderer& renderer, const GaussianCloud& cloud, const Ranking& ranking,
                                const eval::TestViews& views, const QualityBudget& budget,
                                const RenderSettings& settings,
                                const std::function<void(const BudgetProbe&)>& on_probe) {
    if (!(budget.max_psnr_drop >= 0.0))
        throw InputError("--max-psnr-drop " + std::to_string(budget.max_psnr_drop), "must be 0 or more (dB)");
    if (ranking.size() != cloud.size())
        throw std::invalid_argument("prune::fit_quality_budget: the ranking is not of this cloud");
    BudgetResult result;
    if (views.photos) result.baseline_psnr = eval::measure_quality(renderer, cloud, views, settings, false).mean_psnr;

    const auto probe = [&](size_t kept, int sh_degree) {
        const auto start = std::chrono::steady_clock::now();
        GaussianCloud model = cloud.subset(ranking.keep_best(kept));
        if (sh_degree != model.sh_degree) model = model.with_sh_degree(sh_degree);
        if (budget.refit) model = budget.refit(model);
        const eval::Quality quality = eval::measure_quality(renderer, model, views, settings, false);
        BudgetProbe p;
        p.kept = kept;
        p.sh_degree = sh_degree;
        p.psnr = quality.mean_psnr;
        p.drop = psnr_drop(quality, views, result.baseline_psnr, budget.assumed_psnr);
        p.meets = p.drop <= budget.max_psnr_drop;
        p.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        result.probes.push_back(p);
        if (on_probe) on_probe(p);
        if (budget.refit && p.meets) result.model = std::move(model);  // bisection: the last that meets is chosen
        return p;
    };

    // Everything the lossless pass left must meet the budget for the bisection to have a top end.
    BudgetProbe best = probe(ranking.candidates(), cloud.sh_degree);
    result.met = best.meets;
    if (best.meets) {
        size_t low = 0, high = ranking.candidates();  // the answer lies in [low, high]; high meets
        while (low < high) {
            const size_t mid = low + (high - low) / 2;
            const BudgetProbe p = probe(mid, cloud.sh_degree);
            if (p.meets) {
                high = mid;
                best = p;
            } else {
                low = mid + 1;
            }
        }
        if (budget.allow_sh_reduction)
            for (int degree = cloud.sh_degree - 1; degree >= 0; --degree) {
                const BudgetProbe p = probe(best.kept, degree);
                if (!p.meets) break;
                best = p;
            }
    }
    result.kept = best.kept;
    result.sh_degree = best.sh_degree;
    result.psnr = best.psnr;
    result.drop = best.drop;
    result.keep = ranking.keep_best(best.kept);
    return result;
}

}  // namespace vksplat::prune
