#include "util/InterruptSignal.h"

#include <gtest/gtest.h>

#include <csignal>

namespace prism {
namespace {

TEST(InterruptSignal, SigintAndSigtermOnlyRaiseTheFlag) {
  installInterruptHandlers();
  clearInterruptForTesting();
  EXPECT_FALSE(interruptRequested());
  EXPECT_STREQ(interruptSignalName(), "");
  std::raise(SIGTERM);  // without the handler this would end the test process
  EXPECT_TRUE(interruptRequested());
  EXPECT_STREQ(interruptSignalName(), "SIGTERM");
  clearInterruptForTesting();
  std::raise(SIGINT);
  EXPECT_STREQ(interruptSignalName(), "SIGINT");
  clearInterruptForTesting();
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
}

TEST(InterruptSignal, ASecondSignalEndsTheProcessAtOnce) {
  EXPECT_EXIT(
      {
        installInterruptHandlers();
        std::raise(SIGINT);
        std::raise(SIGINT);
        std::_Exit(0);  // not reached
      },
      ::testing::KilledBySignal(SIGINT), "");
}

}  // namespace
}  // namespace prism
