#include "slave/Heartbeat.h"

#include <gtest/gtest.h>

#include <chrono>
#include <mutex>
#include <thread>

#include "slave/FrameBook.h"
#include "transport/LoopbackTransport.h"
#include "wire/Messages.h"

namespace prism {
namespace {

// The next Progress rank 0 receives within 10 s.
std::optional<wire::ProgressMessage> nextBeat(Transport& master) {
  const std::optional<IncomingMessage> m = master.waitForMessage(10.0);
  if (!m) return std::nullopt;
  return wire::decode<wire::ProgressMessage>(wire::decodeMessage(m->bytes));
}

TEST(Heartbeat, SendsTheFrameBooksProgressOnePerRunningFrame) {
  LoopbackNetwork network(2);
  std::mutex shared;
  FrameBook frames;
  {
    const std::lock_guard<std::mutex> lock(shared);
    frames.startView(1, 1, {});
    FrameWork& work = frames.startView(2, 1, {});
    work.received = 5;
    work.held = {3, 4};
  }
  Heartbeat heartbeat(network.endpoint(1), shared, frames);
  const std::optional<wire::ProgressMessage> first = nextBeat(network.endpoint(0));
  const std::optional<wire::ProgressMessage> second = nextBeat(network.endpoint(0));
  heartbeat.stop();
  ASSERT_TRUE(first && second);
  EXPECT_EQ(first->frame, 1u);
  EXPECT_EQ(second->frame, 2u);
  EXPECT_EQ(second->jobsReceived, 5u);
  EXPECT_EQ(second->heldTiles, (std::vector<uint32_t>{3, 4}));
  EXPECT_FALSE(heartbeat.masterGone());
}

// A beat that cannot be sent: rank 0 is gone.
TEST(Heartbeat, NoticesThatRankZeroIsGone) {
  LoopbackNetwork network(2);
  std::mutex shared;
  FrameBook frames;
  network.disconnect(0);
  Heartbeat heartbeat(network.endpoint(1), shared, frames);
  while (!heartbeat.masterGone()) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  heartbeat.stop();
  EXPECT_TRUE(heartbeat.masterGone());
}

}  // namespace
}  // namespace prism
