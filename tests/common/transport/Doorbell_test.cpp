#include "transport/Doorbell.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <string>
#include <thread>

#include "HangGuard.h"

namespace prism {
namespace {

using Clock = std::chrono::steady_clock;

// Unique on the machine: tests of several processes may run at once.
std::string bellName(const char* what) {
  return std::string("prism-test-") + std::to_string(::getpid()) + "-" + what;
}

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

TEST(Doorbell, APeersRingEndsTheWaitAtOnce) {
  Doorbell sender(bellName("sender"));
  Doorbell receiver(bellName("receiver"));
  ASSERT_TRUE(sender.reachable());
  ASSERT_TRUE(receiver.reachable());
  const auto start = Clock::now();
  std::thread ring([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
    EXPECT_TRUE(sender.ring(bellName("receiver")));
  });
  // Peer, not Nothing: woken by the ring, not timed out (the timeout only guards a hang).
  EXPECT_EQ(receiver.wait(test::kHangSeconds), Doorbell::Heard::Peer);
  const double waited = secondsSince(start);
  ring.join();
  EXPECT_GE(waited, 0.025);  // and not before it
}

TEST(Doorbell, WithoutARingTheWaitLastsItsTime) {
  Doorbell bell(bellName("quiet"));
  const auto start = Clock::now();
  EXPECT_EQ(bell.wait(0.04), Doorbell::Heard::Nothing);
  EXPECT_GE(secondsSince(start), 0.035);
}

TEST(Doorbell, RingsBeforeTheWaitAreHeardOnceAndNotLost) {
  Doorbell sender(bellName("early-sender"));
  Doorbell receiver(bellName("early-receiver"));
  for (int i = 0; i < 1000; ++i) EXPECT_TRUE(sender.ring(bellName("early-receiver")));
  EXPECT_EQ(receiver.wait(test::kHangSeconds), Doorbell::Heard::Peer);
  EXPECT_EQ(receiver.wait(0.01), Doorbell::Heard::Nothing);  // every ring heard at once
}

TEST(Doorbell, ItsOwnRingIsToldApartFromAPeers) {
  Doorbell peer(bellName("peer"));
  Doorbell bell(bellName("self"));
  ASSERT_TRUE(peer.ring(bellName("self")));
  bell.ringSelf();
  EXPECT_EQ(bell.wait(10.0), Doorbell::Heard::Self);
  EXPECT_EQ(bell.wait(0.01), Doorbell::Heard::Nothing);
  ASSERT_TRUE(peer.ring(bellName("self")));
  EXPECT_EQ(bell.wait(10.0), Doorbell::Heard::Peer);
}

TEST(Doorbell, RingingANameNobodyHoldsFails) {
  const Doorbell bell(bellName("lonely"));
  EXPECT_FALSE(bell.ring(bellName("nobody")));
}

// What MpiSession relies on to notice a peer on this machine has ended (without Open MPI, which
// may never fail a send to a dead rank): its bell rings while its process lives, never after.
TEST(Doorbell, ABellStopsAnsweringWhenItsProcessEnds) {
  int toChild[2];
  int fromChild[2];
  ASSERT_EQ(::pipe(toChild), 0);
  ASSERT_EQ(::pipe(fromChild), 0);
  const std::string name = bellName("child");  // the parent's pid in it, for both processes
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const Doorbell bell(name);
    char byte = bell.reachable() ? 1 : 0;
    [[maybe_unused]] ssize_t n = ::write(fromChild[1], &byte, 1);  // bound (or not)
    n = ::read(toChild[0], &byte, 1);                              // until told to end
    ::_exit(0);
  }
  char bound = 0;
  ASSERT_EQ(::read(fromChild[0], &bound, 1), 1);
  ASSERT_EQ(bound, 1);
  const Doorbell parent;
  EXPECT_TRUE(parent.ring(name));
  const char end = 1;
  ASSERT_EQ(::write(toChild[1], &end, 1), 1);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_FALSE(parent.ring(name));
  for (int fd : {toChild[0], toChild[1], fromChild[0], fromChild[1]}) ::close(fd);
}

TEST(Doorbell, ANameTakenAlreadyGivesABellOnlyItsProcessRings) {
  Doorbell first(bellName("taken"));
  Doorbell second(bellName("taken"));
  EXPECT_TRUE(first.reachable());
  EXPECT_FALSE(second.reachable());
  const Doorbell unnamed;
  EXPECT_FALSE(unnamed.reachable());
  second.ringSelf();
  EXPECT_EQ(second.wait(10.0), Doorbell::Heard::Self);
  // A ring for the name reaches the bell that holds it.
  ASSERT_TRUE(unnamed.ring(bellName("taken")));
  EXPECT_EQ(first.wait(10.0), Doorbell::Heard::Peer);
}

TEST(Doorbell, ANameIsFreeAgainOnceItsBellIsGone) {
  { const Doorbell gone(bellName("reused")); }
  const Doorbell again(bellName("reused"));
  EXPECT_TRUE(again.reachable());
}

}  // namespace
}  // namespace prism
