#include "progress.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace vksplat::cli {

ProgressLine::ProgressLine(std::string what)
    : what_(std::move(what)), start_(std::chrono::steady_clock::now()), terminal_(isatty(STDERR_FILENO)) {}

void ProgressLine::update(size_t done, size_t total) {
    if (total == 0) return;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    print(done, total,
          done > 0 ? duration_text(elapsed * double(total - done) / double(done)) + " left" : "estimating time left");
}

void ProgressLine::update(size_t done, size_t total, std::optional<double> run_seconds_left) {
    if (total == 0) return;
    print(done, total, run_seconds_left ? duration_text(*run_seconds_left) + " left in all" : "time left in all: estimating");
}

void ProgressLine::print(size_t done, size_t total, const std::string& left) {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const size_t decile = done * 10 / total;
    if (!terminal_ && decile == last_decile_ && done != total) return;
    last_decile_ = decile;
    std::fprintf(stderr, "%s%s %zu/%zu  %s elapsed, %s%s", terminal_ ? "\r" : "", what_.c_str(), done, total,
                 duration_text(elapsed).c_str(), left.c_str(), terminal_ && done != total ? "   " : "\n");
    std::fflush(stderr);
}

std::string duration_text(double seconds) {
    char text[64];
    if (seconds > 0 && seconds < 0.05) return "<0.1 s";  // not "0.0 s" while there is work left
    if (seconds < 60) {
        std::snprintf(text, sizeof(text), "%.1f s", seconds);
    } else if (seconds < 3600) {
        const long whole = std::lround(seconds);
        std::snprintf(text, sizeof(text), "%ld min %02ld s", whole / 60, whole % 60);
    } else {
        const long minutes = std::lround(seconds / 60);
        std::snprintf(text, sizeof(text), "%ld h %02ld min", minutes / 60, minutes % 60);
    }
    return text;
}

}  // namespace vksplat::cli
