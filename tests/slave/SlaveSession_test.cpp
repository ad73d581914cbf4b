// The slave session's life (slave/SlaveSession.h) over the loopback transport: the scene and
// Ready, the end at rank 0's Shutdown, and each way it ends otherwise: a message it cannot read,
// a scene it cannot build, no scene, rank 0 silent or gone.
#include "slave/SlaveSession.h"

#include <gtest/gtest.h>

#include "scene/Scene.h"
#include "slave/SlaveUnderTest.h"
#include "util/InstructionSet.h"
#include "util/Parallel.h"

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
  // Between Hello and Ready only its answer to the scene, with what it builds on.
  ASSERT_EQ(slave.seen().size(), 2u);
  EXPECT_EQ(slave.seen()[0], Type::SceneAccepted);
  EXPECT_EQ(slave.seen()[1], Type::Ready);
  const auto accepted =
      wire::decode<wire::SceneAcceptedMessage>(wire::decodeMessage(slave.raw().at(0)));
  EXPECT_EQ(accepted.threads, availableCores());
  EXPECT_EQ(accepted.cores, machineCores());
  EXPECT_EQ(accepted.ranksOnNode, 2);  // both loopback ranks are threads of this process
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

// Its answer to the scene comes before any rank builds: rank 0 then ends the job, broadcasting
// an Error where the go-ahead would be, and the slave leaves without waiting for a Shutdown.
TEST(SlaveSession, ASceneItCannotReadIsReportedBeforeAnyRankBuilds) {
  SlaveUnderTest slave;
  slave.broadcastAlone(wire::encodeMessage(Type::Scene, {1, 2, 3}));
  const std::optional<wire::Message> answer = slave.nextAnswer();
  ASSERT_TRUE(answer);
  ASSERT_EQ(answer->type, Type::Error);
  EXPECT_EQ(wire::decode<wire::ErrorMessage>(*answer).text.rfind("cannot build the scene: ", 0),
            0u);
  std::vector<uint8_t> plan = wire::encode(wire::ErrorMessage{"rank 1 refused the scene"});
  slave.master().broadcast(plan, 10.0);
  EXPECT_EQ(slave.join().exitCode, 1);
  EXPECT_EQ(slave.count(Type::Ready), 0u);
}

// In set-up a slave takes only what the message list says rank 0 sends then: a message of the
// run in the scene's place is refused like a scene it cannot read.
TEST(SlaveSession, AMessageOfTheRunInsteadOfTheSceneIsRefusedBeforeAnyRankBuilds) {
  SlaveUnderTest slave;
  slave.broadcastAlone(wire::encode(wire::PhotonCancelMessage{1}));
  const std::optional<wire::Message> answer = slave.nextAnswer();
  ASSERT_TRUE(answer);
  ASSERT_EQ(answer->type, Type::Error);
  EXPECT_EQ(wire::decode<wire::ErrorMessage>(*answer).text,
            "cannot build the scene: rank 0 sent PhotonCancel while the job was being set up");
  std::vector<uint8_t> plan = wire::encode(wire::ErrorMessage{"rank 1 refused the scene"});
  slave.master().broadcast(plan, 10.0);
  EXPECT_EQ(slave.join().exitCode, 1);
  EXPECT_EQ(slave.count(Type::Ready), 0u);
}

// Rank 0's own build in place of the go-ahead: the slave takes it as it is and says Ready.
TEST(SlaveSession, TheGeometryRankZeroBuiltIsTakenInsteadOfABuild) {
  SlaveUnderTest slave;
  const SceneDescription d = test::smallScene();
  slave.broadcastBytes(wire::encodeScene(d), wire::encode(Scene(d).geometry()));
  EXPECT_EQ(slave.count(Type::SceneAccepted), 1u);
  ASSERT_TRUE(slave.ready());
  EXPECT_EQ(slave.shutDown().back(), Type::Shutdown);
  EXPECT_EQ(slave.join().exitCode, 0);
}

// A geometry that is not the description's (another scene's, here) is refused, not rendered.
TEST(SlaveSession, AGeometryOfAnotherSceneIsRefused) {
  SlaveUnderTest slave;
  SceneDescription other = test::smallScene();
  other.spheres.push_back(other.spheres.empty() ? SphereDesc{} : other.spheres.back());
  slave.broadcastBytes(wire::encodeScene(test::smallScene()),
                       wire::encode(Scene(other).geometry()));
  const std::optional<wire::Message> error = slave.next(Type::Error);
  ASSERT_TRUE(error);
  EXPECT_NE(wire::decode<wire::ErrorMessage>(*error).text.find("built from another scene"),
            std::string::npos);
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
