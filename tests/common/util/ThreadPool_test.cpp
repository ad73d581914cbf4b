// The parallel loops' threads: started once and reused, every index run once, nested loops
// finished, and a call's exception rethrown to the loop's caller.
#include "util/ThreadPool.h"

#include <gtest/gtest.h>

#include <atomic>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "util/Parallel.h"

namespace prism {
namespace {

// Loops of `threads` indices that each wait until every index has begun: so each index runs on
// a thread of its own, and every thread of the loop is counted. Each thread counts the loops it
// served in a thread_local counter, which a thread started for one loop alone would begin anew.
TEST(ThreadPool, TheSameThreadsServeRepeatedLoops) {
  constexpr int kThreads = 3;
  constexpr int kLoops = 5;
  ThreadPool pool;
  std::mutex mutex;
  // Per thread: its counter at the first loop it served here and at the last.
  std::map<std::thread::id, std::pair<int, int>> served;
  for (int loop = 0; loop < kLoops; ++loop) {
    std::atomic<int> arrived{0};
    pool.run(kThreads, kThreads, [&](uint64_t) {
      thread_local int loopsHere = 0;
      ++loopsHere;
      ++arrived;
      while (arrived < kThreads) std::this_thread::yield();
      const std::lock_guard<std::mutex> lock(mutex);
      const auto [it, first] = served.try_emplace(std::this_thread::get_id(), loopsHere, 0);
      it->second.second = loopsHere;
    });
  }
  EXPECT_EQ(pool.threadCount(), static_cast<size_t>(kThreads - 1));
  ASSERT_EQ(served.size(), static_cast<size_t>(kThreads));  // the caller and two pool threads
  for (const auto& [thread, counts] : served) EXPECT_EQ(counts.second - counts.first, kLoops - 1);
}

TEST(ThreadPool, ParallelForStartsNoThreadsOnceThePoolHasThem) {
  std::atomic<uint64_t> sum{0};
  parallelFor(64, 2, [&](uint64_t i) { sum += i; });
  const size_t threads = ThreadPool::shared().threadCount();
  EXPECT_GE(threads, 1u);
  for (int loop = 0; loop < 20; ++loop) parallelFor(64, 2, [&](uint64_t i) { sum += i; });
  EXPECT_EQ(ThreadPool::shared().threadCount(), threads);
  EXPECT_EQ(sum, 21u * (63u * 64u / 2));
}

TEST(ThreadPool, EveryIndexRunsOnceWhateverTheThreads) {
  ThreadPool pool;
  for (int threads : {1, 2, 3, 8}) {
    for (uint64_t count : {0u, 1u, 7u, 5000u}) {
      std::vector<std::atomic<int>> runs(count);
      pool.run(count, threads, [&](uint64_t i) { ++runs[i]; });
      for (uint64_t i = 0; i < count; ++i) ASSERT_EQ(runs[i], 1) << threads << " threads";
    }
  }
}

// A loop inside a loop's call (a BVH build's halves each bin on two threads): the pool grows
// for the inner loops instead of waiting for threads the outer loop holds.
TEST(ThreadPool, NestedLoopsFinish) {
  ThreadPool pool;
  std::vector<std::atomic<int>> runs(4 * 100);
  pool.run(4, 4, [&](uint64_t outer) {
    pool.run(100, 2, [&](uint64_t inner) { ++runs[outer * 100 + inner]; });
  });
  for (const std::atomic<int>& r : runs) EXPECT_EQ(r, 1);
}

// The exception leaves the loop on whichever thread it was thrown: the caller gets it once the
// other threads are out of the loop, and the pool serves the next loop as before.
TEST(ThreadPool, AnExceptionReachesTheCallerAndThePoolGoesOn) {
  ThreadPool pool;
  for (int thrower : {0, 1, 999}) {
    try {
      pool.run(1000, 3, [&](uint64_t i) {
        if (i == static_cast<uint64_t>(thrower)) {
          throw std::runtime_error("index " + std::to_string(i));
        }
      });
      ADD_FAILURE() << "no exception from index " << thrower;
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), "index " + std::to_string(thrower));
    }
  }
  std::atomic<int> runs{0};
  pool.run(100, 3, [&](uint64_t) { ++runs; });
  EXPECT_EQ(runs, 100);
  EXPECT_THROW(parallelFor(10, 2,
                           [](uint64_t i) {
                             if (i == 5) throw std::logic_error("five");
                           }),
               std::logic_error);
}

}  // namespace
}  // namespace prism
