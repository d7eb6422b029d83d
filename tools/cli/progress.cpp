#include "progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace vksplat::cli {

ProgressLine::ProgressLine(std::string what)
    : what_(std::move(what)), start_(std::chrono::steady_clock::now()), terminal_(isatty(STDERR_FILENO)) {}

void ProgressLine::update(size_t done, size_t total) {
    if (total == 0) return;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double left = done > 0 ? elapsed * double(total - done) / double(done) : 0.0;
    const size_t decile = done * 10 / total;
    if (!terminal_ && decile == last_decile_ && done != total) return;
    last_decile_ = decile;
    std::fprintf(stderr, "%s%s %zu/%zu  %.1f s elapsed, %.1f s left%s", terminal_ ? "\r" : "", what_.c_str(), done,
                 total, elapsed, left, terminal_ && done != total ? "   " : "\n");
    std::fflush(stderr);
}

}  // namespace vksplat::cli
