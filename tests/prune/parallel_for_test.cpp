// The prune module's host threads (prune/parallel_for.hpp): every item once, on the worker the
// item's index names, and an item's exception thrown to the caller, not ending the process.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <vector>

#include "prune/parallel_for.hpp"

namespace vksplat::test {
namespace {

TEST(ParallelFor, RunsEveryItemOnceOnTheWorkerItsIndexNames) {
    for (unsigned workers : {1u, 3u, 8u}) {
        std::vector<std::atomic<int>> runs(100);
        std::vector<unsigned> worker_of(100, 99);
        prune::parallel_for(runs.size(), workers, [&](size_t item, unsigned worker) {
            ++runs[item];
            worker_of[item] = worker;
        });
        for (size_t item = 0; item < runs.size(); ++item) {
            EXPECT_EQ(runs[item], 1) << item;
            EXPECT_EQ(worker_of[item], item % workers) << item;
        }
    }
}

TEST(ParallelFor, AnItemsExceptionReachesTheCallerOnceEveryThreadHasStopped) {
    std::atomic<int> done{0};
    EXPECT_THROW(prune::parallel_for(40, 4,
                                     [&](size_t item, unsigned) {
                                         if (item == 13) throw std::runtime_error("item 13");
                                         ++done;
                                     }),
                 std::runtime_error);
    // Worker 1 stops at item 13 (its items 1, 5, 9 ran); the other three ran all ten of theirs.
    EXPECT_EQ(done.load(), 33);
}

}  // namespace
}  // namespace vksplat::test
