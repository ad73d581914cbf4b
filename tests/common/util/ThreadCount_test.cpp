// A rank's thread count: what the command line names, or every core available to the rank.
#include "util/ThreadCount.h"

#include <gtest/gtest.h>

namespace prism {
namespace {

TEST(ThreadCount, ANamedCountIsKept) {
  EXPECT_EQ(ThreadCount::resolve(1).value(), 1);
  EXPECT_EQ(ThreadCount::resolve(3).value(), 3);
  EXPECT_EQ(ThreadCount::resolve(machineCores() + 5).value(), machineCores() + 5);
}

TEST(ThreadCount, NoneNamedIsEveryAvailableCore) {
  EXPECT_EQ(ThreadCount::resolve(0).value(), availableCores());
  EXPECT_EQ(ThreadCount::resolve(-2).value(), availableCores());
  EXPECT_GE(ThreadCount::resolve(0).value(), 1);
}

}  // namespace
}  // namespace prism
