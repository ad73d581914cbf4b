// The roster's records: a rank's counts add up over frames and subtract between two readings of
// the roster as one operation each (RankStats += and -=), so a frame's share and a run's total
// are computed the same way everywhere.
#include "master/dispatch/SlaveLink.h"

#include <gtest/gtest.h>

namespace prism {
namespace {

// A rank's record with every count and fact set (binary fractions: sums and differences exact).
RankStats rankSoFar() {
  RankStats s;
  s.rank = 2;
  s.threads = 4;
  s.tiles = 7;
  s.rays.primary = 100;
  s.rays.shadow = 50;
  s.rays.secondary = 25;
  s.rays.nonFinite = 1;
  s.busySeconds = 1.5;
  s.buildSeconds = 0.25;
  s.startSeconds = 0.125;
  s.mpiInitSeconds = 0.0625;
  s.staleTiles = 3;
  s.lostTiles = 2;
  return s;
}

// One frame's counts of the same rank, with no facts known.
RankStats oneFrame() {
  RankStats f;
  f.rank = 2;
  f.tiles = 5;
  f.rays.primary = 40;
  f.rays.shadow = 30;
  f.rays.secondary = 20;
  f.rays.nonFinite = 2;
  f.busySeconds = 0.75;
  f.staleTiles = 1;
  f.lostTiles = 4;
  return f;
}

void expectSameRecord(const RankStats& a, const RankStats& b) {
  EXPECT_EQ(a.rank, b.rank);
  EXPECT_EQ(a.threads, b.threads);
  EXPECT_EQ(a.tiles, b.tiles);
  EXPECT_EQ(a.rays.primary, b.rays.primary);
  EXPECT_EQ(a.rays.shadow, b.rays.shadow);
  EXPECT_EQ(a.rays.secondary, b.rays.secondary);
  EXPECT_EQ(a.rays.nonFinite, b.rays.nonFinite);
  EXPECT_EQ(a.busySeconds, b.busySeconds);
  EXPECT_EQ(a.buildSeconds, b.buildSeconds);
  EXPECT_EQ(a.startSeconds, b.startSeconds);
  EXPECT_EQ(a.mpiInitSeconds, b.mpiInitSeconds);
  EXPECT_EQ(a.staleTiles, b.staleTiles);
  EXPECT_EQ(a.lostTiles, b.lostTiles);
  EXPECT_EQ(a.retired, b.retired);
}

TEST(RankStats, AddingAFrameAddsEveryCount) {
  RankStats sum = rankSoFar();
  sum += oneFrame();
  EXPECT_EQ(sum.tiles, 12u);
  EXPECT_EQ(sum.rays.primary, 140u);
  EXPECT_EQ(sum.rays.shadow, 80u);
  EXPECT_EQ(sum.rays.secondary, 45u);
  EXPECT_EQ(sum.rays.nonFinite, 3u);
  EXPECT_EQ(sum.busySeconds, 2.25);
  EXPECT_EQ(sum.staleTiles, 4u);
  EXPECT_EQ(sum.lostTiles, 6u);
}

TEST(RankStats, AddingThenSubtractingAFrameGivesTheRecordBack) {
  RankStats record = rankSoFar();
  record += oneFrame();
  record -= oneFrame();
  expectSameRecord(record, rankSoFar());
}

// A frame's share is the roster after it less the roster before it: the counts' difference,
// the facts as they are after.
TEST(RankStats, SubtractingAnEarlierReadingKeepsTheLaterFacts) {
  RankStats after = rankSoFar();
  after.threads = 8;
  after.retired = true;
  RankStats before = rankSoFar();
  before.tiles = 2;
  before.busySeconds = 0.5;
  RankStats share = after;
  share -= before;
  EXPECT_EQ(share.tiles, 5u);
  EXPECT_EQ(share.busySeconds, 1.0);
  EXPECT_EQ(share.rays.primary, 0u);
  EXPECT_EQ(share.threads, 8);
  EXPECT_TRUE(share.retired);
  EXPECT_EQ(share.buildSeconds, 0.25);
}

// A later frame's facts replace the earlier ones where it knows them; a rank once retired stays so.
TEST(RankStats, AddingTakesTheLaterFactsWhereKnown) {
  RankStats total = rankSoFar();
  total.retired = true;
  RankStats later = oneFrame();
  later.threads = 6;
  later.buildSeconds = 0.5;
  total += later;
  EXPECT_EQ(total.threads, 6);
  EXPECT_EQ(total.buildSeconds, 0.5);
  EXPECT_EQ(total.startSeconds, 0.125);  // the later record does not know it (-1)
  EXPECT_EQ(total.mpiInitSeconds, 0.0625);
  EXPECT_TRUE(total.retired);
}

}  // namespace
}  // namespace prism
