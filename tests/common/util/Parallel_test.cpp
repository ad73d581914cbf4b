#include "util/Parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <vector>

namespace prism {
namespace {

TEST(Parallel, AvailableCoresIsWithinTheMachine) {
  EXPECT_GE(availableCores(), 1);
  EXPECT_LE(availableCores(), machineCores());
}

TEST(Parallel, EveryIndexRunsExactlyOnceForAnyThreadCount) {
  for (int threads : {0, 1, 2, 3, 16}) {
    for (uint64_t count : {0u, 1u, 5u, 1000u}) {
      std::vector<std::atomic<int>> runs(count);
      parallelFor(count, threads, [&](uint64_t i) { ++runs[i]; });
      for (uint64_t i = 0; i < count; ++i) {
        EXPECT_EQ(runs[i], 1) << "threads " << threads << ", index " << i << " of " << count;
      }
    }
  }
}

}  // namespace
}  // namespace prism
