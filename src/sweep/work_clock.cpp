#include "work_clock.hpp"

#include <algorithm>
#include <utility>

namespace vksplat::sweep::detail {
namespace {

double seconds_between(WorkClock::Clock::time_point from, WorkClock::Clock::time_point to) {
    return std::chrono::duration<double>(to - from).count();
}

// What a kind not yet timed costs, as a multiple of another's: a sheet is a render and an image
// written; a plain view costs at most a scoring view; a scoring view is a render with statistics.
std::optional<std::pair<Work, double>> borrowed_cost(Work kind) {
    switch (kind) {
        case Work::sheet: return std::pair{Work::render, 2.0};
        case Work::plain_view: return std::pair{Work::scoring_view, 1.0};
        case Work::scoring_view: return std::pair{Work::render, 1.5};
        default: return std::nullopt;
    }
}

}  // namespace

void WorkClock::plan(Work kind, double pieces) { tally(kind).planned += pieces; }

void WorkClock::begin(Work kind) {
    end();
    current_ = kind;
    since_ = Clock::now();
}

void WorkClock::advance(double pieces) {
    if (!current_) return;
    const Clock::time_point at = Clock::now();
    Tally& t = tally(*current_);
    t.seconds += seconds_between(since_, at);
    t.done += pieces;
    since_ = at;
}

void WorkClock::end() {
    if (!current_) return;
    tally(*current_).seconds += seconds_between(since_, Clock::now());
    current_.reset();
}

std::optional<double> WorkClock::cost(Work kind) const {
    const Tally& t = tally(kind);
    if (t.done > 0) return t.seconds / t.done;
    if (const auto borrowed = borrowed_cost(kind))
        if (const auto other = cost(borrowed->first)) return *other * borrowed->second;
    return std::nullopt;
}

std::optional<double> WorkClock::seconds_left() const {
    double left = 0;
    for (size_t k = 0; k < kKinds; ++k) {
        const Work kind = static_cast<Work>(k);
        const double pieces = tally(kind).planned - tally(kind).done;
        if (pieces <= 0) continue;
        const std::optional<double> each = cost(kind);
        if (!each) return std::nullopt;
        left += pieces * *each;
        // The piece under way has run a while (counted as at most 90% done, so that work left never
        // reads as none).
        if (current_ == kind) left -= std::min(seconds_between(since_, Clock::now()), 0.9 * *each);
    }
    return std::max(left, 0.0);
}

}  // namespace vksplat::sweep::detail
