#pragma once
// A one-line progress display for long runs: views done / total, elapsed and time left.
// Written to stderr, redrawn in place on a terminal, one line per 10% otherwise (logs, CI).
#include <chrono>
#include <cstddef>
#include <optional>
#include <string>

namespace vksplat::cli {

class ProgressLine {
public:
    explicit ProgressLine(std::string what);
    // The stage's time left, from its own rate so far ("estimating" until a step is done).
    void update(size_t done, size_t total);
    // The time the whole run has left, as the job estimates it (nullopt: "estimating"), for runs of
    // many stages whose own rates say nothing of what follows (vksplat sweep).
    void update(size_t done, size_t total, std::optional<double> run_seconds_left);

private:
    void print(size_t done, size_t total, const std::string& left);

    std::string what_;
    std::chrono::steady_clock::time_point start_;
    bool terminal_;
    size_t last_decile_ = 0;
};

// "4.2 s", "3 min 05 s", "1 h 02 min": a duration as a person reads it.
std::string duration_text(double seconds);

}  // namespace vksplat::cli
