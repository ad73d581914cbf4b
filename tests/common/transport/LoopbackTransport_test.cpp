#include "transport/LoopbackTransport.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "HangGuard.h"

namespace prism {
namespace {

std::vector<uint8_t> bytes(std::initializer_list<uint8_t> b) {
  return b;
}

TEST(LoopbackTransport, MessagesArriveInOrderWithTheirSource) {
  LoopbackNetwork network(3);
  EXPECT_EQ(network.endpoint(2).rank(), 2);
  EXPECT_EQ(network.endpoint(2).size(), 3);
  ASSERT_TRUE(network.endpoint(1).send(0, bytes({1})));
  ASSERT_TRUE(network.endpoint(2).send(0, bytes({2})));
  ASSERT_TRUE(network.endpoint(1).send(0, bytes({3})));
  for (const auto& [source, value] : {std::pair{1, 1}, {2, 2}, {1, 3}}) {
    const auto m = network.endpoint(0).poll();
    ASSERT_TRUE(m.has_value());
    EXPECT_EQ(m->source, source);
    EXPECT_EQ(m->bytes, bytes({static_cast<uint8_t>(value)}));
  }
  EXPECT_FALSE(network.endpoint(0).poll().has_value());
  EXPECT_EQ(network.deliveredTo(0), 3u);
}

TEST(LoopbackTransport, WaitingEndsWithAMessageOrTheTimeout) {
  LoopbackNetwork network(2);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(network.endpoint(0).waitForMessage(0.05).has_value());
  EXPECT_GE(std::chrono::steady_clock::now() - start, std::chrono::milliseconds(45));
  std::thread sender([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    network.endpoint(1).send(0, bytes({9}));
  });
  const auto m = network.endpoint(0).waitForMessage(test::kHangSeconds);
  sender.join();
  ASSERT_TRUE(m.has_value());
  EXPECT_EQ(m->bytes, bytes({9}));
}

TEST(LoopbackTransport, WakeEndsTheNextWaitEarlyButNotAPoll) {
  LoopbackNetwork network(2);
  Transport& rank0 = network.endpoint(0);
  rank0.wake();
  EXPECT_FALSE(rank0.poll().has_value());  // a poll does not use the wake-up up
  // Waits that never time out within the test: only the wake-up can end them.
  EXPECT_FALSE(
      test::unlessItHangs([&] { return rank0.waitForMessage(test::kNeverSeconds); }).has_value());
  auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(rank0.waitForMessage(0.03).has_value());  // heard once: this one times out
  EXPECT_GE(std::chrono::steady_clock::now() - start, std::chrono::milliseconds(25));
  // From another thread, during the wait.
  std::thread waker([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    rank0.wake();
  });
  test::unlessItHangs([&] { rank0.awaitActivity(test::kNeverSeconds); });
  waker.join();
  EXPECT_TRUE(rank0.wakesOnMessage());
}

TEST(LoopbackTransport, AwaitingActivityEndsWithAMessageAndLeavesItQueued) {
  LoopbackNetwork network(2);
  std::thread sender([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    network.endpoint(1).send(0, bytes({7}));
  });
  // A wait that never times out within the test: only the message can end it.
  test::unlessItHangs([&] { network.endpoint(0).awaitActivity(test::kNeverSeconds); });
  sender.join();
  const auto m = network.endpoint(0).poll();
  ASSERT_TRUE(m.has_value());
  EXPECT_EQ(m->bytes, bytes({7}));
}

TEST(LoopbackTransport, BroadcastReachesEveryRankAndTimesOutWithoutOne) {
  LoopbackNetwork network(3);
  std::vector<uint8_t> none;
  EXPECT_THROW(network.endpoint(1).broadcast(none, 0.02), TransportError);
  std::vector<uint8_t> scene = bytes({4, 5, 6});
  network.endpoint(0).broadcast(scene, 1.0);
  for (int r = 1; r < 3; ++r) {
    std::vector<uint8_t> got;
    network.endpoint(r).broadcast(got, 1.0);
    EXPECT_EQ(got, scene);
  }
}

TEST(LoopbackTransport, ADisconnectedRankRefusesSendsBothWaysAndLosesItsQueue) {
  LoopbackNetwork network(2);
  ASSERT_TRUE(network.endpoint(0).send(1, bytes({1})));
  network.disconnect(1);
  EXPECT_FALSE(network.connected(1));
  EXPECT_FALSE(network.endpoint(0).send(1, bytes({2})));
  EXPECT_FALSE(network.endpoint(1).send(0, bytes({3})));
  EXPECT_FALSE(network.endpoint(1).poll().has_value());
  EXPECT_THROW(network.endpoint(0).send(5, bytes({1})), TransportError);
  EXPECT_THROW(network.endpoint(0).abortJob(3), TransportError);
}

}  // namespace
}  // namespace prism
