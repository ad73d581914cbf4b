#include "cluster/FaultInjection.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace prism {
namespace {

TEST(FaultInjection, ParsesEachKindWithARank) {
  EXPECT_EQ(parseFaultInjection("hang:2").kind, FaultInjection::Kind::Hang);
  EXPECT_EQ(parseFaultInjection("drop:1").kind, FaultInjection::Kind::DropTiles);
  EXPECT_EQ(parseFaultInjection("slow:1").kind, FaultInjection::Kind::Slow);
  EXPECT_EQ(parseFaultInjection("crash-photons:2").kind, FaultInjection::Kind::CrashOnPhotons);
  EXPECT_EQ(parseFaultInjection("crash-photons:2").rank, 2);
  const FaultInjection crash = parseFaultInjection("crash:3");
  EXPECT_EQ(crash.kind, FaultInjection::Kind::Crash);
  EXPECT_TRUE(crash.appliesTo(3));
  EXPECT_FALSE(crash.appliesTo(2));
}

TEST(FaultInjection, RejectsMalformedText) {
  for (const char* text :
       {"hang", "hang:", "hang:0", "hang:-1", "hang:2x", "melt:2", ":2", "", "slow:0",
        "crash-photons", "crash-photons:0", "crash-photon:1", "crash:photons:1"}) {
    EXPECT_THROW(parseFaultInjection(text), std::invalid_argument) << text;
  }
}

TEST(FaultInjection, TheErrorListsEveryAcceptedForm) {
  try {
    parseFaultInjection("melt:2");
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "fault injection 'melt:2' must be hang:RANK, drop:RANK, crash:RANK, "
              "crash-photons:RANK or slow:RANK with a slave rank >= 1");
  }
}

TEST(FaultInjection, NoneAppliesToNobody) {
  EXPECT_FALSE(FaultInjection{}.appliesTo(1));
}

}  // namespace
}  // namespace prism
