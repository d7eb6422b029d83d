#pragma once
// A one-line progress display for long runs: views done / total, elapsed and time left.
// Written to stderr, redrawn in place on a terminal, one line per 10% otherwise (logs, CI).
#include <chrono>
#include <cstddef>
#include <string>

namespace vksplat::cli {

class ProgressLine {
public:
    explicit ProgressLine(std::string what);
    void update(size_t done, size_t total);

private:
    std::string what_;
    std::chrono::steady_clock::time_point start_;
    bool terminal_;
    size_t last_decile_ = 0;
};

}  // namespace vksplat::cli
