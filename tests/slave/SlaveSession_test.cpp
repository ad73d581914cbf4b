// The slave session's life (slave/SlaveSession.h) over the loopback transport: the scene and
// Ready, the end at rank 0's Shutdown, and each way it ends otherwise: a message it cannot read,
// a scene it cannot build, no scene, rank 0 silent or gone.
#include "slave/SlaveSession.h"

#include <gtest/gtest.h>

#include "slave/SlaveUnderTest.h"
#include "util/InstructionSet.h"

namespace prism {
namespace {

using test::SlaveUnderTest;
using Type = wire::MessageType;

// First what its CPU runs (before the scene, so rank 0 can choose the job's instruction set),
// then Ready once the scene is built.
TEST(SlaveSession, SaysHelloFirstAndReadyWithItsThreadsOnceTheSceneIsBuilt) {
  SlaveUnderTest slave;
  slave.broadcast(test::smallScene());
  ASSERT_TRUE(slave.hello());
  EXPECT_EQ(slave.hello()->instructionSets, runnableInstructionSets());
  EXPECT_EQ(slave.hello()->cpu, cpuModelName());
  const std::optional<wire::Message> ready = slave.next(Type::Ready);
  ASSERT_TRUE(ready);
  EXPECT_EQ(wire::decode<wire::ReadyMessage>(*ready).threads, 1);
  EXPECT_EQ(slave.seen().front(), Type::Ready);  // nothing between Hello and Ready
}

TEST(SlaveSession, AShutdownIsAcknowledgedAndTheSessionEnds) {
  SlaveUnderTest slave;
  slave.broadcast(test::smallScene());
  ASSERT_TRUE(slave.ready());
  const std::vector<Type> end = slave.shutDown();
  ASSERT_FALSE(end.empty());
  EXPECT_EQ(end.back(), Type::Shutdown);
  EXPECT_EQ(std::count(end.begin(), end.end(), Type::Error), 0);
  const SlaveEnd how = slave.join();
  EXPECT_EQ(how.exitCode, 0);
  EXPECT_FALSE(how.masterLost);
}

// A message that is no message: the slave reports it, then waits for rank 0's Shutdown.
TEST(SlaveSession, AMalformedMessageIsReportedToRankZero) {
  SlaveUnderTest slave;
  slave.broadcast(test::smallScene());
  ASSERT_TRUE(slave.ready());
  slave.send({'n', 'o', 't', ' ', 'a', ' ', 'm', 'e', 's', 's', 'a', 'g', 'e'});
  const std::optional<wire::Message> error = slave.next(Type::Error);
  ASSERT_TRUE(error);
  EXPECT_FALSE(wire::decode<wire::ErrorMessage>(*error).text.empty());
  EXPECT_EQ(slave.shutDown().back(), Type::Shutdown);
  EXPECT_EQ(slave.join().exitCode, 1);
}

// A truncated message of a known type is as much an error as bytes that are no message.
TEST(SlaveSession, ATileJobThatDoesNotDecodeIsReportedToRankZero) {
  SlaveUnderTest slave;
  slave.broadcast(test::smallScene());
  ASSERT_TRUE(slave.ready());
  slave.send(wire::encodeMessage(Type::TileJob, {1, 2, 3}));
  ASSERT_TRUE(slave.next(Type::Error));
  EXPECT_EQ(slave.shutDown().back(), Type::Shutdown);
  EXPECT_EQ(slave.join().exitCode, 1);
}

TEST(SlaveSession, ASceneItCannotBuildIsReportedAndTheShutdownAwaited) {
  SlaveUnderTest slave;
  slave.broadcastBytes(wire::encodeMessage(Type::Scene, {1, 2, 3}));
  const std::optional<wire::Message> error = slave.next(Type::Error);
  ASSERT_TRUE(error);
  EXPECT_EQ(wire::decode<wire::ErrorMessage>(*error).text.rfind("cannot build the scene: ", 0), 0u);
  EXPECT_EQ(slave.count(Type::Ready), 0u);
  EXPECT_EQ(slave.shutDown().back(), Type::Shutdown);
  EXPECT_EQ(slave.join().exitCode, 1);
}

// Rank 0 could not read the scene and broadcast its error instead: it reports it; the slave
// ends without a word.
TEST(SlaveSession, AnErrorBroadcastInsteadOfASceneEndsItQuietly) {
  SlaveUnderTest slave;
  slave.broadcastBytes(wire::encode(wire::ErrorMessage{"bad.yaml:2:3: no"}));
  const SlaveEnd how = slave.join();
  EXPECT_EQ(how.exitCode, 1);
  EXPECT_FALSE(how.masterLost);
  EXPECT_FALSE(slave.master().poll());
}

TEST(SlaveSession, NoSceneWithinTheMasterTimeoutEndsIt) {
  SlaveUnderTest slave(test::slaveOptions(0.2));
  const SlaveEnd how = slave.join();
  EXPECT_EQ(how.exitCode, 1);
  EXPECT_TRUE(how.masterLost);
}

// Rank 0 says nothing for longer than masterTimeoutSeconds: the slave gives up on it (and
// does not wait for a Shutdown that will not come).
TEST(SlaveSession, ARankZeroSilentPastTheTimeoutIsGivenUp) {
  // Read before the slave starts: its wait for the scene is bounded by the same 0.3 s, and
  // reading the scene's files (a mesh, a sky) can take longer than that on a slow build. Without
  // the sky: decoding its six 1024² faces from the wire and building their mip levels took the
  // slave past 0.3 s on a loaded machine, and the silence that matters here comes after Ready.
  SceneDescription scene = test::smallScene();
  scene.environment.reset();
  SlaveUnderTest slave(test::slaveOptions(0.3));
  slave.broadcast(scene);
  ASSERT_TRUE(slave.ready());
  const SlaveEnd how = slave.join();
  EXPECT_EQ(how.exitCode, 1);
  EXPECT_TRUE(how.masterLost);
  EXPECT_EQ(slave.count(Type::Error), 0u);
}

// Rank 0 is gone (its sends and ours fail, as under `mpirun --enable-recovery`): the slave
// notices at its next send, the heartbeat's at the latest.
TEST(SlaveSession, ARankZeroThatIsGoneEndsIt) {
  SlaveUnderTest slave;
  slave.broadcast(test::smallScene());
  ASSERT_TRUE(slave.ready());
  slave.network().disconnect(0);
  const SlaveEnd how = slave.join();
  EXPECT_EQ(how.exitCode, 1);
  EXPECT_TRUE(how.masterLost);
}

}  // namespace
}  // namespace prism
