#include "slave/ShutdownWait.h"

#include <gtest/gtest.h>

#include "transport/LoopbackTransport.h"
#include "wire/Messages.h"

namespace prism {
namespace {

TEST(ShutdownWait, AcknowledgesTheShutdownAfterDroppingWhatCameBeforeIt) {
  LoopbackNetwork network(2);
  network.endpoint(0).send(1, wire::encode(wire::EchoMessage{1, ""}));
  network.endpoint(0).send(1, {1, 2, 3});  // malformed: dropped too
  network.endpoint(0).send(1, wire::encode(wire::ShutdownMessage{}));
  EXPECT_TRUE(awaitShutdown(network.endpoint(1), 30.0));
  const std::optional<IncomingMessage> ack = network.endpoint(0).poll();
  ASSERT_TRUE(ack);
  EXPECT_EQ(wire::decodeMessage(ack->bytes).type, wire::MessageType::Shutdown);
  EXPECT_FALSE(network.endpoint(0).poll());  // the echo was not answered
}

TEST(ShutdownWait, GivesUpWithoutAShutdown) {
  LoopbackNetwork network(2);
  network.endpoint(0).send(1, wire::encode(wire::EchoMessage{1, ""}));
  EXPECT_FALSE(awaitShutdown(network.endpoint(1), 0.2));
  EXPECT_FALSE(network.endpoint(0).poll());
}

}  // namespace
}  // namespace prism
