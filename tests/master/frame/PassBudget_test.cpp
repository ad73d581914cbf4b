#include "master/frame/PassBudget.h"

#include <gtest/gtest.h>

namespace prism {
namespace {

// A pass starts only if, as long as the longest so far, it ends with the write still in the
// budget: 3.3 s, 0.2 s for the write, passes of up to 1 s.
TEST(PassBudget, APassStartsOnlyIfItAndTheWriteFitInTheBudget) {
  const PassBudget budget{3.3, 0.2};
  EXPECT_TRUE(startsPass(budget, 2, 2.0, 1.0));        // ends at 3.0, written by 3.2
  EXPECT_FALSE(startsPass(budget, 2, 2.2, 1.0));       // would be written at 3.4
  EXPECT_FALSE(startsPass(budget, 9, 3.2, 0.0));       // even a pass of no time: the write
  EXPECT_TRUE(startsPass({4.0, 0.25}, 2, 2.75, 1.0));  // written at the budget exactly
}

TEST(PassBudget, TheFirstPassAlwaysStartsAndNoBudgetStopsNothing) {
  EXPECT_TRUE(startsPass({3.3, 0.2}, 1, 100.0, 0.0));  // set-up alone past the budget
  EXPECT_TRUE(startsPass({0.0, 0.2}, 50, 1e6, 1e3));   // no budget
}

TEST(PassBudget, TheWriteIsBudgetedByThePixelCount) {
  EXPECT_DOUBLE_EQ(budgetedWriteSeconds(1000000), 0.2);
  EXPECT_DOUBLE_EQ(budgetedWriteSeconds(0), 0.0);
  EXPECT_NEAR(budgetedWriteSeconds(1024 * 1024), 0.2097, 1e-4);
}

}  // namespace
}  // namespace prism
