// Each fault kind as the messages it lets through, drops, rewrites or holds back (slave/
// FaultInjectingTransport.h): first around a bare loopback endpoint, message by message, then
// around a real slave session (runSlave with --inject-fault's options).
#include "slave/FaultInjectingTransport.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "fuzz/WireExamples.h"
#include "slave/SlaveUnderTest.h"
#include "transport/LoopbackTransport.h"
#include "wire/GeometryCodec.h"

namespace prism {
namespace {

using Type = wire::MessageType;

// Rank 0 and a faulty rank 1 of a loopback job, with a clock the test moves.
struct FaultyLink {
  explicit FaultyLink(FaultInjection::Kind kind)
      : faulty(network.endpoint(1), kind, [this] { return now; }) {}

  Transport& master() { return network.endpoint(0); }
  // What rank 1 takes in from what is waiting for it.
  std::vector<Type> received() {
    std::vector<Type> types;
    while (const std::optional<IncomingMessage> m = faulty.poll()) {
      types.push_back(wire::decodeMessage(m->bytes).type);
    }
    return types;
  }
  // What has reached rank 0.
  std::vector<wire::Message> delivered() {
    std::vector<wire::Message> messages;
    while (const std::optional<IncomingMessage> m = master().poll()) {
      messages.push_back(wire::decodeMessage(m->bytes));
    }
    return messages;
  }

  LoopbackNetwork network{2};
  double now = 100.0;
  FaultInjectingTransport faulty;
};

std::vector<Type> typesOf(const std::vector<wire::Message>& messages) {
  std::vector<Type> types;
  for (const wire::Message& m : messages) types.push_back(m.type);
  return types;
}

wire::TileResultMessage tileResult(uint32_t frame, uint32_t tile) {
  wire::TileResultMessage r;
  r.frame = frame;
  r.result.tileIndex = tile;
  r.result.rect = {0, 0, 1, 1};
  r.result.pixels = {Color(0.5f)};
  return r;
}

std::vector<uint8_t> tileJob(uint32_t frame, uint32_t tile) {
  return wire::encode(wire::TileJobMessage{frame, tile, {0, 0, 8, 8}, 0, wire::kTermDirect});
}

TEST(FaultInjectingTransport, HangSwallowsTheWorkAndTheAnswersAndLetsTheRestThrough) {
  FaultyLink link(FaultInjection::Kind::Hang);
  for (std::vector<uint8_t> m :
       {tileJob(1, 0), wire::encode(wire::ViewMessage{1, 1, {}}),
        wire::encode(wire::PhotonJobMessage{1, 0, 10, 10}),
        wire::encode(wire::PhotonRadiiJobMessage{1, 0, 10}),
        wire::encode(wire::PhotonMapMessage{1, {}, {}, false}),
        wire::encode(wire::EchoMessage{1, ""}), wire::encode(wire::ShutdownMessage{})}) {
    link.master().send(1, std::move(m));
  }
  EXPECT_EQ(link.received(),
            (std::vector<Type>{Type::View, Type::PhotonMap, Type::Echo, Type::Shutdown}));
  for (std::vector<uint8_t> m :
       {wire::encode(wire::ReadyMessage{0.1, 1}), wire::encode(tileResult(1, 0)),
        wire::encode(wire::ProgressMessage{1, 1, {0}}),
        wire::encode(wire::PhotonShareMessage{1, 0, 10, {}, 0.0, {}}),
        wire::encode(wire::PhotonRadiiShareMessage{1, 0, {}}),
        wire::encode(wire::EchoMessage{1, ""}), wire::encode(wire::ErrorMessage{"x"}),
        wire::encode(wire::ShutdownMessage{})}) {
    EXPECT_TRUE(link.faulty.send(0, std::move(m)));  // as if sent
  }
  EXPECT_EQ(typesOf(link.delivered()),
            (std::vector<Type>{Type::Ready, Type::Echo, Type::Error, Type::Shutdown}));
}

// The same for every message of the list, each way it may travel: a hanging rank takes in and
// sends out exactly the messages whose role is Control.
TEST(FaultInjectingTransport, HangLetsThroughEveryControlMessageOfTheListAndNothingElse) {
  FaultyLink link(FaultInjection::Kind::Hang);
  std::vector<Type> toSlave, toMaster, controlToSlave, controlToMaster;
  wire::forEachMessageType([&](auto type) {
    using T = typename decltype(type)::type;
    const Type t = wire::MessageTraits<T>::kType;
    const std::vector<uint8_t> bytes = fuzz::acceptedExamples<T>().at(0).bytes;
    const bool control = wire::kindOf(t).role == wire::Role::Control;
    if (wire::goesTo(t, wire::Direction::ToSlave)) {
      link.master().send(1, bytes);
      toSlave.push_back(t);
      if (control) controlToSlave.push_back(t);
    }
    if (wire::goesTo(t, wire::Direction::ToMaster)) {
      EXPECT_TRUE(link.faulty.send(0, bytes));  // as if sent
      toMaster.push_back(t);
      if (control) controlToMaster.push_back(t);
    }
  });
  EXPECT_EQ(link.received(), controlToSlave);
  EXPECT_EQ(typesOf(link.delivered()), controlToMaster);
  // Each way carries work or answers as well as control, or the test would prove little.
  EXPECT_LT(controlToSlave.size(), toSlave.size());
  EXPECT_LT(controlToMaster.size(), toMaster.size());
}

// Every second TileJob of each frame is swallowed, yet counted in the Progress of its frame as
// received: rank 0 sees it received and not held.
TEST(FaultInjectingTransport, DropSwallowsEverySecondTileJobOfAFrameAndCountsItReceived) {
  FaultyLink link(FaultInjection::Kind::DropTiles);
  for (uint32_t tile = 0; tile < 5; ++tile) link.master().send(1, tileJob(1, tile));
  for (uint32_t tile = 0; tile < 2; ++tile) link.master().send(1, tileJob(2, tile));
  std::vector<std::pair<uint32_t, uint32_t>> taken;  // (frame, tile)
  while (const std::optional<IncomingMessage> m = link.faulty.poll()) {
    const wire::TileJobMessage job =
        wire::decode<wire::TileJobMessage>(wire::decodeMessage(m->bytes));
    taken.emplace_back(job.frame, job.tileIndex);
  }
  EXPECT_EQ(taken, (std::vector<std::pair<uint32_t, uint32_t>>{{1, 0}, {1, 2}, {1, 4}, {2, 0}}));
  link.faulty.send(0, wire::encode(wire::ProgressMessage{1, 3, {4}}));
  link.faulty.send(0, wire::encode(wire::ProgressMessage{2, 1, {}}));
  link.faulty.send(0, wire::encode(wire::ProgressMessage{3, 0, {}}));
  const std::vector<wire::Message> sent = link.delivered();
  ASSERT_EQ(sent.size(), 3u);
  EXPECT_EQ(wire::decode<wire::ProgressMessage>(sent[0]).jobsReceived, 5u);
  EXPECT_EQ(wire::decode<wire::ProgressMessage>(sent[0]).heldTiles, std::vector<uint32_t>{4});
  EXPECT_EQ(wire::decode<wire::ProgressMessage>(sent[1]).jobsReceived, 2u);
  EXPECT_EQ(wire::decode<wire::ProgressMessage>(sent[2]).jobsReceived, 0u);
}

// A slow rank: each tile result leaves kSlowTileDelaySeconds after the previous one on its
// render thread's lane (two threads here, from Ready), and is held until then.
TEST(FaultInjectingTransport, SlowHoldsEachTileResultBackPerRenderThread) {
  FaultyLink link(FaultInjection::Kind::Slow);
  link.faulty.send(0, wire::encode(wire::ReadyMessage{0.1, 2}));
  for (uint32_t tile = 0; tile < 3; ++tile) {
    EXPECT_TRUE(link.faulty.send(0, wire::encode(tileResult(1, tile))));
  }
  link.faulty.send(0, wire::encode(wire::ProgressMessage{1, 4, {3}}));
  std::vector<wire::Message> sent = link.delivered();
  ASSERT_EQ(typesOf(sent), (std::vector<Type>{Type::Ready, Type::Progress}));
  EXPECT_EQ(wire::decode<wire::ProgressMessage>(sent[1]).heldTiles,
            (std::vector<uint32_t>{0, 1, 2, 3}));
  EXPECT_EQ(link.faulty.heldBack(), 3u);

  link.now += kSlowTileDelaySeconds * 0.99;
  link.faulty.poll();
  EXPECT_TRUE(link.delivered().empty());
  link.now += kSlowTileDelaySeconds * 0.02;  // one delay on: one result per thread
  link.faulty.poll();
  sent = link.delivered();
  ASSERT_EQ(typesOf(sent), (std::vector<Type>{Type::TileResult, Type::TileResult}));
  EXPECT_EQ(wire::decode<wire::TileResultMessage>(sent[0]).result.tileIndex, 0u);
  EXPECT_EQ(wire::decode<wire::TileResultMessage>(sent[1]).result.tileIndex, 1u);
  link.faulty.send(0, wire::encode(wire::ProgressMessage{1, 4, {3}}));
  EXPECT_EQ(wire::decode<wire::ProgressMessage>(link.delivered().at(0)).heldTiles,
            (std::vector<uint32_t>{2, 3}));

  link.now += kSlowTileDelaySeconds;  // two delays on: the third
  link.faulty.progressSends();
  sent = link.delivered();
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(wire::decode<wire::TileResultMessage>(sent[0]).result.tileIndex, 2u);
  EXPECT_EQ(link.faulty.heldBack(), 0u);
}

// One thread (no Ready yet): a result handed over while the lane is idle leaves one delay later;
// one handed over while another waits, one delay after that one.
TEST(FaultInjectingTransport, SlowPacesOneThreadOneDelayPerTile) {
  FaultyLink link(FaultInjection::Kind::Slow);
  const auto at = [&link](double delays) { link.now = 100.0 + delays * kSlowTileDelaySeconds; };
  at(0.0);
  link.faulty.send(0, wire::encode(tileResult(1, 0)));  // leaves at 1
  at(0.5);
  link.faulty.send(0, wire::encode(tileResult(1, 1)));  // leaves at 2
  at(1.05);
  link.faulty.poll();
  EXPECT_EQ(link.delivered().size(), 1u);
  at(1.95);
  link.faulty.poll();
  EXPECT_TRUE(link.delivered().empty());
  at(2.05);
  link.faulty.poll();
  EXPECT_EQ(link.delivered().size(), 1u);
}

// Bytes that are no message pass both ways: the slave, or rank 0, reports them.
TEST(FaultInjectingTransport, MalformedMessagesPassUntouched) {
  for (const FaultInjection::Kind kind :
       {FaultInjection::Kind::Hang, FaultInjection::Kind::DropTiles, FaultInjection::Kind::Slow,
        FaultInjection::Kind::Crash}) {
    FaultyLink link(kind);
    const std::vector<uint8_t> junk = {1, 2, 3};
    link.master().send(1, junk);
    const std::optional<IncomingMessage> in = link.faulty.poll();
    ASSERT_TRUE(in);
    EXPECT_EQ(in->bytes, junk);
    link.faulty.send(0, junk);
    const std::optional<IncomingMessage> out = link.master().poll();
    ASSERT_TRUE(out);
    EXPECT_EQ(out->bytes, junk);
  }
}

// Death tests fork: the threadsafe style re-runs the test in the child, the loopback included.
class FaultInjectingTransportDeathTest : public ::testing::Test {
 protected:
  void SetUp() override { GTEST_FLAG_SET(death_test_style, "threadsafe"); }
};

TEST_F(FaultInjectingTransportDeathTest, CrashDiesOnTheFirstTileJobAsIfKilled) {
  FaultyLink link(FaultInjection::Kind::Crash);
  link.master().send(1, wire::encode(wire::PhotonJobMessage{1, 0, 10, 10}));
  link.master().send(1, wire::encode(wire::EchoMessage{1, ""}));
  EXPECT_EQ(link.received(), (std::vector<Type>{Type::PhotonJob, Type::Echo}));
  link.master().send(1, tileJob(1, 0));
  EXPECT_EXIT(link.faulty.poll(), ::testing::ExitedWithCode(9), "");
}

TEST_F(FaultInjectingTransportDeathTest, CrashPhotonsDiesOnTheFirstPhotonJob) {
  FaultyLink link(FaultInjection::Kind::CrashOnPhotons);
  link.master().send(1, tileJob(1, 0));
  link.master().send(1, wire::encode(wire::PhotonMapMessage{1, {}, {}, false}));
  EXPECT_EQ(link.received(), (std::vector<Type>{Type::TileJob, Type::PhotonMap}));
  link.master().send(1, wire::encode(wire::PhotonJobMessage{2, 0, 10, 10}));
  EXPECT_EXIT(link.faulty.poll(), ::testing::ExitedWithCode(9), "");
}

// ---- around a real slave: runSlave wraps its transport when the fault names its rank -------

DistributionOptions faultyOptions(FaultInjection::Kind kind, int rank = 1) {
  DistributionOptions options = test::slaveOptions();
  options.fault = {kind, rank};
  return options;
}

// A hung slave says Ready, takes its jobs and answers none (no tile, no heartbeat), and still
// acknowledges the Shutdown, so the job ends cleanly.
// (Its answer to the scene, SceneAccepted, passes too: rank 0 waits for it before any build.)
TEST(FaultInjectingTransport, AHungSlaveSaysReadyAndAcknowledgesTheShutdownOnly) {
  test::SlaveUnderTest slave(faultyOptions(FaultInjection::Kind::Hang));
  slave.broadcast(test::smallScene());
  ASSERT_TRUE(slave.ready());
  slave.send(tileJob(1, 0));
  slave.send(wire::encode(wire::PhotonJobMessage{1, 0, 100, 100}));
  std::this_thread::sleep_for(std::chrono::duration<double>(3 * kHeartbeatSeconds));
  EXPECT_EQ(slave.shutDown(), std::vector<Type>{Type::Shutdown});
  EXPECT_EQ(slave.seen(), (std::vector<Type>{Type::SceneAccepted, Type::Ready, Type::Shutdown}));
  EXPECT_EQ(slave.join().exitCode, 0);
}

// A slave that drops tiles renders the others; its heartbeat names the dropped ones received
// and not held, which is how rank 0 finds them lost.
TEST(FaultInjectingTransport, ASlaveThatDropsTilesRendersEveryOtherAndItsHeartbeatShowsThemLost) {
  test::SlaveUnderTest slave(faultyOptions(FaultInjection::Kind::DropTiles));
  slave.broadcast(test::smallScene());
  ASSERT_TRUE(slave.ready());
  for (uint32_t tile = 0; tile < 4; ++tile) slave.send(tileJob(1, tile));
  std::vector<uint32_t> rendered;
  for (int i = 0; i < 2; ++i) {
    const std::optional<wire::Message> m = slave.next(Type::TileResult);
    ASSERT_TRUE(m);
    rendered.push_back(wire::decode<wire::TileResultMessage>(*m).result.tileIndex);
  }
  std::sort(rendered.begin(), rendered.end());
  EXPECT_EQ(rendered, (std::vector<uint32_t>{0, 2}));
  // A beat after both results (the jobs all taken by then): the two others received, none held.
  std::optional<wire::ProgressMessage> beat;
  while (const std::optional<wire::Message> m = slave.next(Type::Progress)) {
    beat = wire::decode<wire::ProgressMessage>(*m);
    if (beat->frame == 1 && beat->jobsReceived == 4) break;
  }
  ASSERT_TRUE(beat);
  EXPECT_EQ(beat->jobsReceived, 4u);
  EXPECT_TRUE(beat->heldTiles.empty());
  EXPECT_EQ(slave.shutDown().back(), Type::Shutdown);
  EXPECT_EQ(slave.count(Type::TileResult), 2u);
}

// A slow slave's tiles all come, the same pixels, while its heartbeat holds the ones not yet
// sent.
TEST(FaultInjectingTransport, ASlowSlaveDeliversEveryTileWithTheSamePixels) {
  const SceneDescription d = test::smallScene();
  const Scene scene(d);
  test::SlaveUnderTest slave(faultyOptions(FaultInjection::Kind::Slow));
  slave.broadcast(d);
  ASSERT_TRUE(slave.ready());
  for (uint32_t tile = 0; tile < 3; ++tile) slave.send(tileJob(1, tile));
  for (int i = 0; i < 3; ++i) {
    const std::optional<wire::Message> m = slave.next(Type::TileResult);
    ASSERT_TRUE(m);
    const wire::TileResultMessage r = wire::decode<wire::TileResultMessage>(*m);
    EXPECT_TRUE(test::samePixels(
        r.result.pixels, TileRenderer(scene).render(r.result.tileIndex, r.result.rect).pixels));
  }
  EXPECT_EQ(slave.shutDown().back(), Type::Shutdown);
}

// The fault names another rank: this one is untouched.
TEST(FaultInjectingTransport, AFaultForAnotherRankLeavesThisOneAlone) {
  test::SlaveUnderTest slave(faultyOptions(FaultInjection::Kind::Hang, 2));
  slave.broadcast(test::smallScene());
  ASSERT_TRUE(slave.ready());
  slave.send(tileJob(1, 0));
  EXPECT_TRUE(slave.next(Type::TileResult));
}

}  // namespace
}  // namespace prism
