#include "util/ProcessStart.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <thread>

namespace prism {
namespace {

TEST(ProcessStart, TheAgeOfThisProcessGrowsWithTheClock) {
  const std::optional<double> before = secondsSinceProcessStart();
  ASSERT_TRUE(before);
  EXPECT_GE(*before, 0.0);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  const std::optional<double> after = secondsSinceProcessStart();
  ASSERT_TRUE(after);
  // /proc/uptime has 10 ms steps: 0.2 s of sleep reads as 0.18 to 0.22 s, and more under load.
  EXPECT_GE(*after - *before, 0.18);
  EXPECT_LT(*after - *before, 5.0);
}

TEST(ProcessStart, AChildStartsAfterItsParentByTheTimeTheParentWaited) {
  // The child is this test's fork, started at least 0.3 s after this process: it reports at least
  // that much (less the 10 ms resolution) through its exit code, in tenths of a second.
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const std::optional<double> fromParent = secondsFromParentStart();
    ::_exit(fromParent ? std::min(static_cast<int>(*fromParent * 10.0 + 0.5), 254) : 255);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  const int tenths = WEXITSTATUS(status);
  ASSERT_NE(tenths, 255) << "/proc could not be read";
  const double age = secondsSinceProcessStart().value_or(0.0);
  EXPECT_GE(tenths, 3);
  EXPECT_LE(tenths, static_cast<int>(age * 10.0 + 1.5));
}

}  // namespace
}  // namespace prism
