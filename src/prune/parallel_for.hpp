#pragma once
// Host work spread over the machine's cores, for the prune module's CPU passes (the Fisher
// reference, the size budget's file searches).
#include <algorithm>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace vksplat::prune {

// Runs fn(item, worker) for item in [0, count) on `workers` threads (at least one), worker w
// taking the items w, w + workers, ...: which worker sums which item depends on nothing but the
// count of workers, so the sums are the same every run on one machine. The first exception an
// item throws is thrown again once every thread has stopped (a thread's own would end the
// process); the other items of that worker are skipped.
template <typename Fn>
void parallel_for(size_t count, unsigned workers, Fn fn) {
    workers = std::max(1u, workers);
    std::exception_ptr failure;
    std::mutex failure_lock;
    const auto work = [&](unsigned worker) {
        try {
            for (size_t item = worker; item < count; item += workers) fn(item, worker);
        } catch (...) {
            const std::lock_guard lock(failure_lock);
            if (!failure) failure = std::current_exception();
        }
    };
    std::vector<std::thread> threads;
    for (unsigned t = 1; t < workers; ++t) threads.emplace_back(work, t);
    work(0);
    for (auto& thread : threads) thread.join();
    if (failure) std::rethrow_exception(failure);
}

inline unsigned worker_count() { return std::max(1u, std::thread::hardware_concurrency()); }

}  // namespace vksplat::prune
