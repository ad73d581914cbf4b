#include "master/analysis/TileScheduleSimulator.h"

#include <gtest/gtest.h>

#include <cmath>

namespace prism {
namespace {

ScheduleSimulation equalTiles(size_t tiles, double cost, int workers) {
  ScheduleSimulation s;
  s.tileSeconds.assign(tiles, cost);
  s.workers = workers;
  return s;
}

// Equal-cost tiles with the link's latency L: the first job arrives after L, a worker then
// renders back to back (prefetch 2 hides the round trip as long as it is shorter than a tile),
// and the last result needs L to come back: ceil(tiles/p)·cost + 2L.
TEST(TileScheduleSimulator, EqualTilesGiveTheAnalyticMakespan) {
  constexpr double kCost = 0.010, kLatency = 0.001;
  for (const auto& [tiles, workers] :
       {std::pair<size_t, int>{10, 3}, {64, 4}, {100, 7}, {33, 1}, {48, 16}}) {
    for (Schedule schedule : {Schedule::Dynamic, Schedule::Static}) {
      ScheduleSimulation s = equalTiles(tiles, kCost, workers);
      s.schedule = schedule;
      s.link.latencySeconds = kLatency;
      const SimulatedFrame f = simulateTileSchedule(s);
      const double rounds = std::ceil(static_cast<double>(tiles) / workers);
      EXPECT_NEAR(f.seconds, rounds * kCost + 2 * kLatency, 1e-12)
          << tiles << " tiles, " << workers << " workers";
      double busy = 0.0;
      size_t done = 0;
      for (int w = 0; w < workers; ++w) {
        busy += f.busySeconds[w];
        done += f.tilesByWorker[w];
      }
      EXPECT_NEAR(busy, tiles * kCost, 1e-9);
      EXPECT_EQ(done, tiles);
    }
  }
}

// Without prefetch every tile waits for its own round trip: ceil(tiles/p)·(cost + 2L).
TEST(TileScheduleSimulator, WithoutPrefetchEveryTilePaysTheRoundTrip) {
  ScheduleSimulation s = equalTiles(20, 0.010, 4);
  s.prefetch = 1;
  s.link.latencySeconds = 0.002;
  EXPECT_NEAR(simulateTileSchedule(s).seconds, 5 * (0.010 + 0.004), 1e-12);
}

// The master's link is shared: p results finishing together reach it one after another.
TEST(TileScheduleSimulator, ResultsQueueOnTheMastersLink) {
  ScheduleSimulation s = equalTiles(4, 0.5, 4);
  s.prefetch = 1;  // one tile each (with 2, worker 0 would be sent tiles 0 and 1)
  s.resultBytes.assign(4, 1000.0);
  s.link.bytesPerSecond = 10000.0;  // 0.1 s per result
  EXPECT_NEAR(simulateTileSchedule(s).seconds, 0.5 + 4 * 0.1, 1e-12);
  // Jobs leave it one after another too: the fourth, 0.05 s each, is out at 0.2 s.
  s.resultBytes.clear();
  s.jobBytes = 500.0;
  EXPECT_NEAR(simulateTileSchedule(s).seconds, 0.2 + 0.5, 1e-12);
}

// Skewed costs [10, 1, 10, 1, ...] on two workers: the static interleave gives worker 0 every
// expensive tile (4 × 10 = 40 s); the pull queue balances them. With no latency and one job in
// flight, list scheduling gives: w0 t0 [0,10], w1 t1 [0,1], t2 [1,11]; w0 t3 [10,11];
// then w1 (its result was scheduled first) t4 [11,21], w0 t5 [11,12], t6 [12,22];
// w1 t7 [21,22]: 22 s.
TEST(TileScheduleSimulator, StaticLosesToDynamicOnASkewedCostMap) {
  ScheduleSimulation s;
  s.tileSeconds = {10, 1, 10, 1, 10, 1, 10, 1};
  s.workers = 2;
  s.prefetch = 1;
  s.schedule = Schedule::Static;
  const SimulatedFrame fixed = simulateTileSchedule(s);
  EXPECT_DOUBLE_EQ(fixed.seconds, 40.0);
  EXPECT_DOUBLE_EQ(fixed.busySeconds[0], 40.0);
  EXPECT_DOUBLE_EQ(fixed.busySeconds[1], 4.0);
  s.schedule = Schedule::Dynamic;
  const SimulatedFrame pulled = simulateTileSchedule(s);
  EXPECT_DOUBLE_EQ(pulled.seconds, 22.0);
  EXPECT_DOUBLE_EQ(pulled.busySeconds[0] + pulled.busySeconds[1], 44.0);
}

TEST(TileScheduleSimulator, ThreadsAndCpuShareScaleAWorker) {
  ScheduleSimulation s = equalTiles(8, 1.0, 1);
  s.threadsPerWorker = 4;
  s.prefetch = 4;
  EXPECT_DOUBLE_EQ(simulateTileSchedule(s).seconds, 2.0);
  s.cpuShare = 0.5;  // two render threads per core: each tile takes twice as long
  EXPECT_DOUBLE_EQ(simulateTileSchedule(s).seconds, 4.0);
}

TEST(TileScheduleSimulator, IsDeterministicAndRejectsNonsense) {
  ScheduleSimulation s;
  for (int i = 0; i < 200; ++i) s.tileSeconds.push_back(0.001 * (1 + (i * 37) % 11));
  s.workers = 9;
  s.link.latencySeconds = 0.0003;
  const SimulatedFrame a = simulateTileSchedule(s);
  const SimulatedFrame b = simulateTileSchedule(s);
  EXPECT_EQ(a.seconds, b.seconds);
  EXPECT_EQ(a.tilesByWorker, b.tilesByWorker);
  s.workers = 0;
  EXPECT_THROW(simulateTileSchedule(s), std::invalid_argument);
  s.workers = 2;
  s.cpuShare = 0.0;
  EXPECT_THROW(simulateTileSchedule(s), std::invalid_argument);
  s.cpuShare = 1.0;
  s.resultBytes = {1.0};
  EXPECT_THROW(simulateTileSchedule(s), std::invalid_argument);
}

}  // namespace
}  // namespace prism
