#include "master/dispatch/TileScheduler.h"

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>

namespace prism {
namespace {

TEST(TileScheduler, DynamicHandsOutTilesInOrderToWhoeverAsks) {
  TileScheduler s(5, 3, Schedule::Dynamic, 10.0);
  EXPECT_EQ(s.next(2, 0.0), 0u);
  EXPECT_EQ(s.next(0, 0.0), 1u);
  EXPECT_EQ(s.next(2, 0.0), 2u);
  EXPECT_EQ(s.outstanding(2), 2u);
}

TEST(TileScheduler, StaticInterleavesTilesByWorker) {
  TileScheduler s(7, 3, Schedule::Static, 10.0);
  std::vector<uint32_t> worker1;
  while (auto t = s.next(1, 0.0)) worker1.push_back(*t);
  EXPECT_EQ(worker1, (std::vector<uint32_t>{1, 4}));
  EXPECT_EQ(s.next(0, 0.0), 0u);
  EXPECT_EQ(s.next(0, 0.0), 3u);
}

// `prism speedup` leaves rank 0 and some slaves out: they get nothing, and the static
// interleave runs over the active workers only.
TEST(TileScheduler, IdleWorkersTakeNoTilesUnderEitherSchedule) {
  const std::vector<bool> active{false, true, true, false};
  TileScheduler fixed(5, 4, Schedule::Static, 10.0, active);
  EXPECT_TRUE(fixed.idle(0));
  EXPECT_FALSE(fixed.next(0, 0.0));
  EXPECT_FALSE(fixed.next(3, 0.0));
  std::vector<uint32_t> worker1, worker2;
  while (auto t = fixed.next(1, 0.0)) worker1.push_back(*t);
  while (auto t = fixed.next(2, 0.0)) worker2.push_back(*t);
  EXPECT_EQ(worker1, (std::vector<uint32_t>{0, 2, 4}));
  EXPECT_EQ(worker2, (std::vector<uint32_t>{1, 3}));

  TileScheduler pulled(3, 4, Schedule::Dynamic, 10.0, active);
  EXPECT_FALSE(pulled.next(3, 0.0));
  EXPECT_EQ(pulled.next(2, 0.0), 0u);
  pulled.retire(2);  // its tile goes back to the queue, still not to an idle worker
  EXPECT_FALSE(pulled.next(0, 0.0));
  EXPECT_EQ(pulled.next(1, 0.0), 0u);
  EXPECT_THROW(TileScheduler(3, 2, Schedule::Dynamic, 10.0, {false, false}), std::invalid_argument);
}

TEST(TileScheduler, CompletionIsCountedOnceAndDuplicatesAreRejected) {
  TileScheduler s(2, 2, Schedule::Dynamic, 10.0);
  const uint32_t a = *s.next(0, 0.0);
  const uint32_t b = *s.next(1, 0.0);
  EXPECT_TRUE(s.complete(a, 0, 1.0));
  EXPECT_FALSE(s.complete(a, 0, 1.0));  // duplicate
  EXPECT_FALSE(s.complete(7, 0, 1.0));  // out of range
  EXPECT_FALSE(s.finished());
  EXPECT_TRUE(s.complete(b, 1, 1.0));
  EXPECT_TRUE(s.finished());
}

TEST(TileScheduler, NeverIssuedTileCannotBeCompleted) {
  TileScheduler s(3, 1, Schedule::Dynamic, 10.0);
  EXPECT_FALSE(s.complete(2, 0, 0.0));
  EXPECT_EQ(s.doneCount(), 0u);
}

TEST(TileScheduler, SilentWorkerIsRetiredAndItsTilesComeBackFirst) {
  TileScheduler s(6, 2, Schedule::Dynamic, 5.0);
  s.exemptFromLeases(0);
  const uint32_t t0 = *s.next(1, 0.0);
  const uint32_t t1 = *s.next(1, 0.0);
  EXPECT_TRUE(s.reclaimExpired(4.0).empty());  // still within the lease
  EXPECT_EQ(s.reclaimExpired(6.0), std::vector<int>{1});
  EXPECT_TRUE(s.retired(1));
  EXPECT_EQ(s.reissuedCount(), 2u);
  EXPECT_FALSE(s.next(1, 6.0).has_value());  // no more work for a retired worker
  EXPECT_EQ(s.next(0, 6.0), t0);             // its tiles first, in order
  EXPECT_EQ(s.next(0, 6.0), t1);
  // A late answer from the retired worker still counts if it comes first...
  EXPECT_TRUE(s.complete(t1, 1, 7.0));
  // ...and the re-issued copy is then a duplicate.
  EXPECT_FALSE(s.complete(t1, 0, 8.0));
}

TEST(TileScheduler, ResultsKeepAWorkerAlive) {
  TileScheduler s(10, 2, Schedule::Dynamic, 5.0);
  const uint32_t a = *s.next(1, 0.0);
  s.next(1, 0.0);
  EXPECT_TRUE(s.complete(a, 1, 4.0));
  EXPECT_TRUE(s.reclaimExpired(8.0).empty());  // heard from it at 4 s
  EXPECT_EQ(s.reclaimExpired(9.5), std::vector<int>{1});
}

TEST(TileScheduler, ExemptWorkerIsNeverRetired) {
  TileScheduler s(2, 1, Schedule::Dynamic, 1.0);
  s.exemptFromLeases(0);
  s.next(0, 0.0);
  EXPECT_TRUE(s.reclaimExpired(100.0).empty());
}

TEST(TileScheduler, StaticScheduleHandsARetiredWorkersShareToOthers) {
  TileScheduler s(6, 2, Schedule::Static, 1.0);
  s.exemptFromLeases(0);
  s.next(1, 0.0);  // tile 1 leased to worker 1, which then goes silent
  s.reclaimExpired(2.0);
  std::set<uint32_t> got;
  while (auto t = s.next(0, 2.0)) got.insert(*t);
  EXPECT_EQ(got, (std::set<uint32_t>{0, 1, 2, 3, 4, 5}));
}

TEST(TileScheduler, ReconcileReissuesOnlyTilesReceivedButNoLongerHeld) {
  TileScheduler s(10, 2, Schedule::Dynamic, 30.0);
  const uint32_t a = *s.next(1, 0.0);  // job 0
  const uint32_t b = *s.next(1, 0.0);  // job 1
  const uint32_t c = *s.next(1, 0.0);  // job 2, still in flight to the worker
  // The worker has received jobs 0 and 1, holds a, and lost b; c has not arrived yet.
  EXPECT_EQ(s.reconcile(1, 2, {a}), 1u);
  EXPECT_EQ(s.outstanding(1), 2u);  // a and c
  EXPECT_EQ(s.reissuedCount(), 1u);
  EXPECT_EQ(s.next(0, 1.0), b);  // the lost tile is first in line
  // A tile delivered before the heartbeat is not reported lost.
  EXPECT_TRUE(s.complete(a, 1, 1.0));
  EXPECT_EQ(s.reconcile(1, 3, {c}), 0u);
  EXPECT_FALSE(s.retired(1));
}

}  // namespace
}  // namespace prism
