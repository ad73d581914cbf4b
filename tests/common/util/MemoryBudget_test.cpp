#include "util/MemoryBudget.h"

#include <gtest/gtest.h>

namespace prism {
namespace {

TEST(MemoryBudget, EachPieceIsCheckedAgainstTheLimitLessTheOnesBefore) {
  MemoryBudget budget(MemoryLimit{1000, "--memory-limit"}, "the meshes before this one");
  EXPECT_EQ(budget.remaining().bytes, 1000u);
  EXPECT_EQ(budget.remaining().source, "--memory-limit");
  budget.spend(300);
  budget.spend(200);
  EXPECT_EQ(budget.remaining().bytes, 500u);
  EXPECT_EQ(budget.remaining().source, "--memory-limit, less the meshes before this one");
  budget.spend(5000);  // more than is left: nothing, never a wrapped-around huge number
  EXPECT_EQ(budget.remaining().bytes, 0u);
}

}  // namespace
}  // namespace prism
