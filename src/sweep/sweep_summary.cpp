// The sweep in one line (summary_line): what pruning buys within 1 dB of the unpruned scene.
#include <cstdio>
#include <string>

#include "vksplat/sweep/sweep.hpp"

namespace vksplat::sweep {
namespace {

// The loss a user still calls "the same scene" at a glance: the 80%-dropped target.
constexpr double kAcceptableLossDb = 1.0;

std::string format(const char* pattern, double value) {
    char text[64];
    std::snprintf(text, sizeof(text), pattern, value);
    return text;
}

std::string percent(double fraction) { return format(fraction >= 0.1 ? "%.0f%%" : "%.1f%%", fraction * 100); }

// "2.1x faster (1.20 -> 0.57 ms per frame)", or slower; empty without timings.
std::string speed(const ModelMeasure& unpruned, const ModelMeasure& pruned, bool cpu) {
    if (!(unpruned.ms_per_frame > 0) || !(pruned.ms_per_frame > 0)) return "";
    const double ratio = unpruned.ms_per_frame / pruned.ms_per_frame;
    return ", " + (ratio >= 1 ? format("%.1fx faster", ratio) : format("%.1fx slower", 1 / ratio)) + " (" +
           format("%.2f", unpruned.ms_per_frame) + " -> " + format("%.2f", pruned.ms_per_frame) + " ms per frame" +
           (cpu ? ", timed on a CPU" : "") + ")";
}

std::string trade(const SweepRow& row, const SweepResult& result) {
    return row.method + ", " + percent(row.dropped) + " fewer Gaussians at " + format("%+.2f dB", row.delta_psnr) +
           speed(result.unpruned, row.measure, result.device_is_cpu);
}

}  // namespace

std::string summary_line(const SweepResult& result) {
    // Rows that drop nothing (fraction 0 where the lossless pass found nothing) trade nothing.
    const SweepRow* best = nullptr;
    for (const SweepRow& row : result.rows)
        if (row.dropped > 0 && row.delta_psnr >= -kAcceptableLossDb &&
            (!best || row.dropped > best->dropped || (row.dropped == best->dropped && row.delta_psnr > best->delta_psnr)))
            best = &row;
    if (best) return "best trade: " + trade(*best, result);
    // Every row loses more: the least loss at the smallest fraction swept that drops any.
    for (const SweepRow& row : result.rows)
        if (row.dropped > 0 && (!best || row.fraction < best->fraction ||
                                (row.fraction == best->fraction && row.delta_psnr > best->delta_psnr)))
            best = &row;
    if (!best) return "no Gaussian was dropped: nothing to trade";
    return "no pruned model stays within " + format("%g", kAcceptableLossDb) + " dB of the unpruned one; the least loss: " +
           trade(*best, result);
}

}  // namespace vksplat::sweep
