// The best model within a file size: per SH choice the most Gaussians that fit, then the one of
// least PSNR drop.
#include "vksplat/prune/size_budget.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <cstdio>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "vksplat/error.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/prune/sh_reduction.hpp"
#include "prune/parallel_for.hpp"

namespace vksplat::prune {
namespace {

namespace fs = std::filesystem;

// The cloud at `degree`, with `share` of its higher bands then dropped per Gaussian, its SH values
// at `precision`.
struct ShChoice {
    int degree = 0;
    double share = 0;
    ShPrecision precision;
};

// `model` rounded to `precision`, or as it is at full precision (what an 8-bit SPZ writer rounds
// anyway, and the other formats on their own grids).
GaussianCloud at_precision(GaussianCloud model, const ShPrecision& precision) {
    return precision == ShPrecision{} ? model : with_sh_precision(model, precision);
}

// The choices size_budget.hpp lists at one precision, the unreduced one first.
std::vector<ShChoice> sh_choices(int degree, const ShPrecision& precision) {
    std::vector<ShChoice> choices;
    const int steps = 2 * degree;
    for (int s = 0; s <= steps; ++s) choices.push_back({degree, steps ? double(s) / double(steps) : 0.0, precision});
    for (int d = degree - 1; d >= 1; --d) choices.push_back({d, 0.0, precision});
    return choices;
}

// The precisions a budget tries: the one it sets, else kSizeBudgetPrecisions.
std::vector<ShPrecision> precisions_of(const SizeBudget& budget) {
    if (budget.sh_precision) return {*budget.sh_precision};
    return {std::begin(kSizeBudgetPrecisions), std::end(kSizeBudgetPrecisions)};
}

// How many count searches run at once: one a core, but no more than a quarter of the host's
// memory holds, each holding about three models as large as the cloud at worst while it writes a
// file (the subset, its bands dropped or rounded, the file's bytes): a tiled scene of millions of
// Gaussians on a machine of many cores would otherwise hold tens of gigabytes.
unsigned search_workers(size_t searches, const GaussianCloud& cloud) {
    const double memory = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
    const double model = double(sizeof(float)) * double(cloud.positions.size() + cloud.log_scales.size() +
                                                        cloud.rotations.size() + cloud.opacity_logits.size() +
                                                        cloud.sh.size());
    const double fit = memory > 0 && model > 0 ? 0.25 * memory / (3.0 * model) : double(worker_count());
    return unsigned(std::clamp<double>(std::min({double(worker_count()), double(searches), fit}), 1.0, 1024.0));
}

std::vector<double> kept_values(std::span<const double> values, const KeepMask& keep) {
    std::vector<double> kept;
    if (values.empty()) return kept;
    for (size_t i = 0; i < keep.size(); ++i)
        if (keep[i]) kept.push_back(values[i]);
    return kept;
}

// Megabytes of 10^6 bytes, as --max-mb takes them.
std::string megabytes(size_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", double(bytes) / 1e6);
    return text;
}

}  // namespace

size_t scene_file_bytes(const GaussianCloud& cloud, const std::string& format) {
    std::string path = (fs::temp_directory_path() / "vksplat-size-XXXXXX").string();
    const int fd = mkstemp(path.data());  // a name no one else holds
    if (fd < 0) throw std::runtime_error("prune::scene_file_bytes: cannot create a temporary file " + path);
    close(fd);
    struct Remove {
        std::string path;
        ~Remove() {
            std::error_code ignored;
            fs::remove(path, ignored);
        }
    } remove{path};
    io::write_scene(cloud, path, io::WriteMode::overwrite, format);
    return fs::file_size(path);
}

size_t largest_fitting(size_t most, size_t max_bytes, const std::function<size_t(size_t)>& bytes_of) {
    if (most == 0) return 0;
    size_t low = 1, low_bytes = bytes_of(1);
    if (low_bytes > max_bytes) return 0;
    // low fits; high, once known (high <= most), does not. Until then the slope comes from the two
    // largest counts that fit (`before` and low): writing every candidate to find the bracket's top
    // would cost the most of any count (bonsai: all 400k Gaussians, 2 s, where a 3 MB model of 90k
    // takes a third of a second), so `most` is tried only where the line says it may fit.
    size_t high = most + 1, high_bytes = 0;
    size_t before = 0, before_bytes = 0;
    const auto try_count = [&](size_t count) {
        const size_t bytes = bytes_of(count);
        if (bytes <= max_bytes) {
            before = low;
            before_bytes = low_bytes;
            low = count;
            low_bytes = bytes;
        } else {
            high = count;
            high_bytes = bytes;
        }
        return bytes;
    };
    // A second count for the slope, small enough to cost little and large enough that a file's
    // fixed part (headers, a compressor's start) does not set it.
    constexpr size_t kSlopeCount = 1024;
    if (most > 1) try_count(std::min(most, kSlopeCount));
    // Each count costs a file written (bonsai at 3 MB: a third of a second), and a choice's search
    // by halving took ~20 of them. A file grows nearly in proportion to its Gaussians, so the count
    // where the line through the counts tried meets the budget lands near the answer, on one side
    // of it; a second count as far past it as the line says it missed by (twice, and at least one)
    // closes the bracket from the other side. Where a file's growth is far from a line and the two
    // do not halve the bracket, the next count halves it: at worst three calls a halving.
    bool halve = false;
    while (high - low > 1) {
        const size_t width = high - low;
        const double per_gaussian = high <= most ? double(high_bytes - low_bytes) / double(width)
                                                 : double(low_bytes - std::min(low_bytes, before_bytes)) /
                                                       double(low - before);
        const size_t guess =
            halve || !(per_gaussian > 0)
                ? low + width / 2
                : std::clamp(low + size_t(std::min(double(max_bytes - low_bytes) / per_gaussian, double(most))),
                             low + 1, high - 1);
        const size_t bytes = try_count(guess);
        if (!halve && high - low > 1 && per_gaussian > 0) {
            const double missed = std::abs(double(max_bytes) - double(bytes)) / per_gaussian;
            const size_t reach = size_t(std::min(2.0 * missed, double(most))) + 1;
            const size_t past = bytes <= max_bytes ? std::min(high - 1, guess + reach)
                                                   : (guess - low > reach ? guess - reach : low + 1);
            if (past > low && past < high) try_count(past);
        }
        halve = high - low > (width + 1) / 2;
    }
    return low;
}

void check_size_reachable(const GaussianCloud& smallest, const SizeBudget& budget) {
    const size_t bytes = scene_file_bytes(smallest, budget.format);
    if (bytes <= budget.max_bytes) return;
    const std::string what = smallest.empty() ? "a scene of no Gaussians" : "one Gaussian at SH degree 0";
    throw InputError("--max-mb " + megabytes(budget.max_bytes),
                     "no model fits in it: the smallest, " + what + ", takes " + std::to_string(bytes) + " bytes (" +
                         megabytes(bytes) + " MB) as " + budget.format);
}

double model_sh_share(const BudgetResult& choice, int cloud_degree) {
    if (!(choice.sh_share > 0) || choice.sh_degree <= 0) return 0;
    const double kept = (1.0 - choice.sh_share) * double(cloud_degree);  // higher bands per Gaussian
    return std::clamp(1.0 - kept / double(choice.sh_degree), 0.0, 1.0);
}

GaussianCloud fit_refitted(const GaussianCloud& refitted, std::span<const double> weights, std::span<const float> scores,
                           double sh_share, const SizeBudget& budget) {
    if (scores.size() != refitted.size())
        throw std::invalid_argument("prune::fit_refitted: the scores are not of the re-fitted model");
    const GaussianCloud reduced =
        at_precision(with_sh_share_dropped(refitted, weights, sh_share), budget.sh_precision.value_or(ShPrecision{}));
    const Ranking ranking(scores, keep_all(reduced.size()));
    const size_t kept = largest_fitting(reduced.size(), budget.max_bytes, [&](size_t count) {
        return scene_file_bytes(reduced.subset(ranking.keep_best(count)), budget.format);
    });
    return kept == reduced.size() ? reduced : reduced.subset(ranking.keep_best(kept));
}

BudgetResult fit_size_budget(Renderer& renderer, const GaussianCloud& cloud, const Ranking& ranking,
                             std::span<const double> weights, const eval::TestViews& views, const SizeBudget& budget,
                             const RenderSettings& settings, const std::function<void(const BudgetProbe&)>& on_probe) {
    if (ranking.size() != cloud.size())
        throw std::invalid_argument("prune::fit_size_budget: the ranking is not of this cloud");
    if (!weights.empty() && weights.size() != cloud.size())
        throw std::invalid_argument("prune::fit_size_budget: the weights are not of this cloud");
    const size_t most = ranking.candidates();
    const auto model_of = [&](size_t kept, const ShChoice& choice) {
        const KeepMask keep = ranking.keep_best(kept);
        GaussianCloud model = cloud.subset(keep);
        if (choice.degree != model.sh_degree) model = model.with_sh_degree(choice.degree);
        if (choice.share > 0) model = with_sh_share_dropped(model, kept_values(weights, keep), choice.share);
        return at_precision(std::move(model), choice.precision);
    };
    // The last per-Gaussian choice drops every higher band: its best Gaussian is the smallest model.
    check_size_reachable(model_of(std::min<size_t>(most, 1), sh_choices(cloud.sh_degree, {})[size_t(2 * cloud.sh_degree)]),
                         budget);

    // The most Gaussians of `choice` (at most `limit`) whose file fits in `max_bytes`, and that
    // file's bytes; the search writes each count's file once.
    struct Fit {
        size_t kept = 0, bytes = 0;
    };
    const auto fit_choice = [&](const ShChoice& choice, size_t limit, size_t max_bytes) {
        std::map<size_t, size_t> sizes;
        const auto bytes_of = [&](size_t kept) {
            auto [entry, fresh] = sizes.try_emplace(kept, 0);
            if (fresh) entry->second = scene_file_bytes(model_of(kept, choice), budget.format);
            return entry->second;
        };
        Fit fit;
        fit.kept = largest_fitting(limit, max_bytes, bytes_of);
        if (fit.kept > 0) fit.bytes = bytes_of(fit.kept);
        return fit;
    };

    BudgetResult result;
    result.met = true;
    if (views.photos) result.baseline_psnr = eval::measure_quality(renderer, cloud, views, settings, false).mean_psnr;
    struct Candidate {
        size_t kept, bytes;
        ShChoice choice;
        double drop;
    };
    std::vector<Candidate> candidates;
    bool chosen_refitted = false;  // once one is, only re-fitted candidates compete
    // Measures a candidate (after budget.refit where `refitted`) and keeps it if it is the best so
    // far of its kind: the re-fitted ones replace the choice by drop as it is.
    const auto probe = [&](size_t kept, const ShChoice& choice, size_t bytes, bool refitted = false) {
        const auto start = std::chrono::steady_clock::now();
        GaussianCloud model = model_of(kept, choice);
        GaussianCloud measured = model;
        if (refitted) {
            // As the re-fitted model is written (fit_refitted): its bands and bits reduced again.
            const KeepMask keep = ranking.keep_best(kept);
            measured = budget.refit(model);
            if (choice.share > 0) measured = with_sh_share_dropped(measured, kept_values(weights, keep), choice.share);
            measured = at_precision(std::move(measured), choice.precision);
            // Re-fitted values compress less well (bonsai's SPZ at 88,518 Gaussians: 9% more), and
            // the Gaussians that then no longer fit would go after the long re-fit, with nothing
            // to make up for them: the count chosen is the one whose file, grown as this one did,
            // fits, so that the rounds re-fit that many. Measured as re-fitted at its own count:
            // cut to the smaller one without a re-fit, the every-band candidates measured worst
            // (bonsai 3 MB, 6,6 bits: -1.25 dB against -0.89) and the choice was a worse one.
            const double growth = double(scene_file_bytes(measured, budget.format)) / double(bytes);
            if (growth > 1.0) {
                const Fit fitting = fit_choice(choice, kept, size_t(double(budget.max_bytes) / growth));
                if (fitting.kept > 0 && fitting.kept < kept) {
                    kept = fitting.kept;
                    bytes = fitting.bytes;
                    model = model_of(kept, choice);
                }
            }
        }
        const eval::Quality quality = eval::measure_quality(renderer, measured, views, settings, false);
        BudgetProbe p;
        p.kept = kept;
        p.sh_degree = model.sh_degree;
        p.sh_share = choice.share;
        p.sh_precision = choice.precision;
        p.bytes = bytes;
        p.psnr = quality.mean_psnr;
        p.drop = psnr_drop(quality, views, result.baseline_psnr, budget.assumed_psnr);
        p.meets = true;
        p.refitted = refitted;
        p.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        result.probes.push_back(p);
        if (on_probe) on_probe(p);
        if (!refitted) candidates.push_back({kept, bytes, choice, p.drop});
        if (!result.model || (refitted && !chosen_refitted) || p.drop < result.drop) {
            chosen_refitted = refitted;
            result.model = std::move(model);
            result.kept = p.kept;
            result.sh_degree = p.sh_degree;
            result.sh_share = p.sh_share;
            result.sh_precision = p.sh_precision;
            result.psnr = p.psnr;
            result.drop = p.drop;
        }
    };

    // Whether a format stores rounded values or dropped bands in fewer bytes is asked of the best
    // `sample` Gaussians' files, not of the whole cloud's: each whole file took as long as the rest
    // of its choice's search (bonsai's 400k as SPZ, 2 s), and there were 18 of them for 27 choices.
    constexpr size_t kSampleCount = 8192;
    const size_t sample = std::min(most, kSampleCount);
    const auto sample_bytes = [&](const ShChoice& choice) {
        return scene_file_bytes(model_of(sample, choice), budget.format);
    };
    struct Search {
        ShChoice choice;
        bool unreduced = false;   // every band of the cloud's degree: if all of it fits, nothing to trade
        Fit fit;
    };
    std::vector<Search> searches;  // in the order they are measured
    size_t full_precision_sample = 0;  // the unreduced sample's file at full precision
    for (const ShPrecision& precision : precisions_of(budget)) {
        size_t unreduced_sample = 0;
        for (const ShChoice& choice : sh_choices(cloud.sh_degree, precision)) {
            const bool unreduced = choice.degree == cloud.sh_degree && choice.share == 0;
            const bool per_gaussian = choice.degree == cloud.sh_degree && choice.share > 0 && choice.share < 1;
            if (unreduced) {
                unreduced_sample = sample_bytes(choice);
                if (precision == ShPrecision{}) {
                    full_precision_sample = unreduced_sample;
                } else if (full_precision_sample > 0 && unreduced_sample >= full_precision_sample) {
                    break;  // the format does not store the rounded values in fewer bytes
                }
            } else if (per_gaussian && sample_bytes(choice) >= unreduced_sample) {
                continue;  // the format does not store these zeros in fewer bytes
            }
            searches.push_back({choice, unreduced, {}});
        }
    }
    // Each choice's count is searched by writing files, host work of seconds a choice on a real
    // scene and independent of the others, so the searches share the cores; the measurements
    // (the GPU's) follow one by one.
    parallel_for(searches.size(), search_workers(searches.size(), cloud), [&](size_t k, unsigned) {
        searches[k].fit = fit_choice(searches[k].choice, most, budget.max_bytes);
    });
    bool all_fit = false;
    for (const Search& search : searches) {
        if (search.fit.kept > 0) probe(search.fit.kept, search.choice, search.fit.bytes);
        if (search.unreduced && search.fit.kept == most) {  // everything fits: nothing to trade
            all_fit = true;
            break;
        }
    }
    if (budget.refit && !all_fit) {
        std::vector<const Candidate*> shortlist;
        const auto add = [&](const Candidate* c) {
            if (c && std::find(shortlist.begin(), shortlist.end(), c) == shortlist.end()) shortlist.push_back(c);
        };
        for (const ShPrecision& precision : precisions_of(budget)) {
            const Candidate *least = nullptr, *every_band = nullptr;
            for (const Candidate& c : candidates) {
                if (!(c.choice.precision == precision)) continue;
                if (!least || c.drop < least->drop) least = &c;
                if (c.choice.degree == cloud.sh_degree && c.choice.share == 0) every_band = &c;
            }
            add(least);
            add(every_band);
        }
        for (const Candidate* c : shortlist) probe(c->kept, c->choice, c->bytes, true);
    }
    result.keep = ranking.keep_best(result.kept);
    return result;
}

}  // namespace vksplat::prune
