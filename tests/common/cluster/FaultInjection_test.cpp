#include "cluster/FaultInjection.h"

#include <gtest/gtest.h>

namespace prism {
namespace {

TEST(FaultInjection, ParsesEachKindWithARank) {
  EXPECT_EQ(parseFaultInjection("hang:2").kind, FaultInjection::Kind::Hang);
  EXPECT_EQ(parseFaultInjection("drop:1").kind, FaultInjection::Kind::DropTiles);
  EXPECT_EQ(parseFaultInjection("slow:1").kind, FaultInjection::Kind::Slow);
  const FaultInjection crash = parseFaultInjection("crash:3");
  EXPECT_EQ(crash.kind, FaultInjection::Kind::Crash);
  EXPECT_TRUE(crash.appliesTo(3));
  EXPECT_FALSE(crash.appliesTo(2));
}

TEST(FaultInjection, RejectsMalformedText) {
  for (const char* text :
       {"hang", "hang:", "hang:0", "hang:-1", "hang:2x", "melt:2", ":2", "", "slow:0"}) {
    EXPECT_THROW(parseFaultInjection(text), std::invalid_argument) << text;
  }
}

TEST(FaultInjection, NoneAppliesToNobody) {
  EXPECT_FALSE(FaultInjection{}.appliesTo(1));
}

}  // namespace
}  // namespace prism
