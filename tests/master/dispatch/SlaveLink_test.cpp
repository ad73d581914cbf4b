// Rank 0's side of its slaves (master/dispatch/SlaveLink.h). The roster's records: a rank's counts
// add up over frames and subtract between two readings as one operation each (RankStats += and
// -=). The one reader of the slaves' messages over the loopback transport, slaves played by the
// test: the set-up's roll calls, the run's receive, the link probe's echo and the shut-down's
// acknowledgements, each checked against the message list.
#include "master/dispatch/SlaveLink.h"

#include <gtest/gtest.h>

#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "transport/LoopbackTransport.h"
#include "wire/Messages.h"

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

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "no error";
}

TEST(SlaveLink, ARollCallReturnsEachSlavesMessageDecodedByRank) {
  LoopbackNetwork network(3);
  network.endpoint(2).send(0, wire::encode(wire::SceneAcceptedMessage{2, 8, 1}));
  network.endpoint(1).send(0, wire::encode(wire::SceneAcceptedMessage{4, 16, 2}));
  const std::vector<wire::SceneAcceptedMessage> answers =
      firstOfEachSlave<wire::SceneAcceptedMessage>(network.endpoint(0), 5.0, "is silent");
  ASSERT_EQ(answers.size(), 3u);
  EXPECT_EQ(answers[1].threads, 4);
  EXPECT_EQ(answers[1].ranksOnNode, 2);
  EXPECT_EQ(answers[2].threads, 2);
  EXPECT_EQ(answers[2].cores, 8);
}

TEST(SlaveLink, ARollCallEndsOnAnErrorAnotherSetUpMessageOrSilenceNamingTheRank) {
  {
    LoopbackNetwork network(2);
    network.endpoint(1).send(0, wire::encode(wire::ErrorMessage{"no memory"}));
    EXPECT_EQ(errorOf([&] {
                firstOfEachSlave<wire::HelloMessage>(network.endpoint(0), 5.0, "is silent");
              }),
              "rank 1: no memory");
  }
  {
    LoopbackNetwork network(2);
    network.endpoint(1).send(0, wire::encode(wire::SceneAcceptedMessage{}));
    EXPECT_EQ(errorOf([&] {
                firstOfEachSlave<wire::HelloMessage>(network.endpoint(0), 5.0, "is silent");
              }),
              "rank 1 sent SceneAccepted before Hello");
  }
  {
    LoopbackNetwork network(2);
    EXPECT_EQ(errorOf([&] {
                firstOfEachSlave<wire::HelloMessage>(network.endpoint(0), 0.05, "is silent");
              }),
              "rank 1 is silent");
  }
}

// Only what the list says a slave sends in set-up has a roll call, and a slave that sends what
// only rank 0 sends ends the run, at any step.
TEST(SlaveLink, TheMessageListDecidesWhatRankZeroTakesFromASlave) {
  LoopbackNetwork network(2);
  EXPECT_THROW(firstOfEachSlave<wire::TileResultMessage>(network.endpoint(0), 0.05, "is silent"),
               std::logic_error);
  EXPECT_THROW(firstOfEachSlave<wire::BuildGeometryMessage>(network.endpoint(0), 0.05, "is silent"),
               std::logic_error);
  network.endpoint(1).send(0, wire::encode(wire::PhotonCancelMessage{3}));
  EXPECT_EQ(
      errorOf([&] { firstOfEachSlave<wire::HelloMessage>(network.endpoint(0), 5.0, "is silent"); }),
      "rank 1 sent PhotonCancel, which only rank 0 sends");

  SlaveLink link(&network.endpoint(0), DistributionOptions{});
  network.endpoint(1).send(0, wire::encode(wire::TileJobMessage{1, 0, {0, 0, 8, 8}, 0, 1}));
  EXPECT_EQ(errorOf([&] { link.receive(5.0); }), "rank 1 sent TileJob, which only rank 0 sends");
  network.endpoint(1).send(0, wire::encode(wire::EchoMessage{7, ""}));
  const std::optional<SlaveMessage> echo = link.receive(5.0);
  ASSERT_TRUE(echo);  // Echo goes both ways
  EXPECT_EQ(echo->message.type, wire::MessageType::Echo);
}

TEST(SlaveLink, AnEchoIsAwaitedPastOtherMessagesAndGivenUpOn) {
  LoopbackNetwork network(2);
  SlaveLink link(&network.endpoint(0), DistributionOptions{});
  network.endpoint(1).send(0, wire::encode(wire::EchoMessage{1, ""}));  // a late one
  network.endpoint(1).send(0, wire::encode(wire::ProgressMessage{}));
  network.endpoint(1).send(0, wire::encode(wire::EchoMessage{2, ""}));
  EXPECT_TRUE(link.awaitEcho(1, 2, 5.0));
  EXPECT_FALSE(link.awaitEcho(1, 3, 0.2));
}

TEST(SlaveLink, ShutdownAcknowledgementsNameTheirRankAndNothingElseCounts) {
  LoopbackNetwork network(3);
  network.endpoint(2).send(0, wire::encode(wire::ProgressMessage{}));
  network.endpoint(2).send(0, wire::encode(wire::ShutdownMessage{}));
  EXPECT_EQ(nextShutdownAcknowledgement(network.endpoint(0), 1.0), std::nullopt);
  EXPECT_EQ(nextShutdownAcknowledgement(network.endpoint(0), 1.0), std::optional<int>(2));
  EXPECT_EQ(nextShutdownAcknowledgement(network.endpoint(0), 0.05), std::nullopt);
}

}  // namespace
}  // namespace prism
