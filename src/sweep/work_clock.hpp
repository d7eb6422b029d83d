#pragma once
// The time a sweep has left: its work in kinds whose pieces cost about the same (a render, a model
// measured, a re-fit iteration, ...), the pieces planned and done of each, and the seconds each kind
// has taken so far. Time left = the sum over kinds of pieces left times their measured cost, less
// the time the piece under way has run. A kind not timed yet borrows another's cost (a comparison
// sheet: two renders), or, with none to borrow (re-fit iterations before the first re-fit has
// stepped), leaves the time left unknown rather than guessed.
#include <array>
#include <chrono>
#include <optional>

namespace vksplat::sweep::detail {

enum class Work {
    render,           // a test view rendered (the unpruned targets, SH degrees)
    measure,          // a model measured: its test views rendered, compared and timed
    scoring_view,     // a training view rendered with statistics; also cluster pruning's region views
    plain_view,       // a training view rendered plainly
    refit_iteration,  // a re-fit step, the re-fit's set-up and rounds' re-scoring shared out over them
    sheet,            // a comparison sheet rendered and written
};

class WorkClock {
public:
    using Clock = std::chrono::steady_clock;

    // Adds pieces of `kind` to the plan (negative: drops pieces that turned out not to be needed).
    void plan(Work kind, double pieces);
    // From now on the time counts towards `kind`, until the next begin or end.
    void begin(Work kind);
    // `pieces` of the kind begun are done: the time since begin (or the last advance) is theirs.
    void advance(double pieces);
    void end();

    // Seconds left, or nullopt while a kind with pieces left has no cost measured or borrowed.
    std::optional<double> seconds_left() const;

private:
    static constexpr size_t kKinds = 6;
    struct Tally {
        double planned = 0, done = 0, seconds = 0;
    };
    std::optional<double> cost(Work kind) const;  // seconds per piece
    Tally& tally(Work kind) { return tally_[static_cast<size_t>(kind)]; }
    const Tally& tally(Work kind) const { return tally_[static_cast<size_t>(kind)]; }

    std::array<Tally, kKinds> tally_{};
    std::optional<Work> current_;
    Clock::time_point since_{};  // the begin or last advance: time since is the piece under way's
};

}  // namespace vksplat::sweep::detail
