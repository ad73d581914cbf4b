#include "util/InstructionSet.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace prism {
namespace {

const InstructionSet kConcrete[] = {InstructionSet::Baseline, InstructionSet::V2,
                                    InstructionSet::V3, InstructionSet::V4};

TEST(InstructionSet, NamesReadBackAndShortFormsAreAccepted) {
  for (InstructionSet isa : kConcrete) {
    EXPECT_EQ(parseInstructionSet(instructionSetName(isa)), isa) << instructionSetName(isa);
  }
  EXPECT_EQ(parseInstructionSet("auto"), InstructionSet::Auto);
  EXPECT_EQ(parseInstructionSet("baseline"), InstructionSet::Baseline);
  EXPECT_EQ(parseInstructionSet("v2"), InstructionSet::V2);
  EXPECT_EQ(parseInstructionSet("v3"), InstructionSet::V3);
  EXPECT_EQ(parseInstructionSet("x86-64-v4"), InstructionSet::V4);
  EXPECT_EQ(parseInstructionSet("v5"), std::nullopt);
  EXPECT_EQ(parseInstructionSet("avx2"), std::nullopt);
  EXPECT_EQ(parseInstructionSet(""), std::nullopt);
}

TEST(InstructionSet, TheBestOfASetAndItsMembersInOrder) {
  EXPECT_EQ(bestInstructionSet(0), InstructionSet::Baseline);
  EXPECT_EQ(bestInstructionSet(maskOf(InstructionSet::Baseline) | maskOf(InstructionSet::V2)),
            InstructionSet::V2);
  EXPECT_EQ(bestInstructionSet(maskOf(InstructionSet::Baseline) | maskOf(InstructionSet::V4)),
            InstructionSet::V4);
  const auto all = instructionSetsIn(maskOf(InstructionSet::V4) | maskOf(InstructionSet::Baseline) |
                                     maskOf(InstructionSet::V3));
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[0], InstructionSet::Baseline);
  EXPECT_EQ(all[1], InstructionSet::V3);
  EXPECT_EQ(all[2], InstructionSet::V4);
}

// What this process runs is nested (each level needs the one below), always holds the
// baseline, and resolves Auto to its best; a set beyond it is refused by name.
TEST(InstructionSet, ThisProcessRunsNestedLevelsAndRefusesTheRest) {
  const InstructionSetMask runnable = runnableInstructionSets();
  ASSERT_TRUE(runnable & maskOf(InstructionSet::Baseline));
  const InstructionSet best = bestInstructionSet(runnable);
  for (InstructionSet isa : kConcrete) {
    EXPECT_EQ((runnable & maskOf(isa)) != 0, isa <= best) << instructionSetName(isa);
  }
  EXPECT_EQ(resolveInstructionSet(InstructionSet::Auto), best);
  for (InstructionSet isa : kConcrete) {
    if (isa <= best) {
      EXPECT_EQ(resolveInstructionSet(isa), isa);
      continue;
    }
    try {
      resolveInstructionSet(isa);
      ADD_FAILURE() << instructionSetName(isa) << " accepted beyond " << instructionSetName(best);
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(instructionSetName(isa)), std::string::npos);
    }
  }
}

TEST(InstructionSet, TheCpuHasAName) {
  const std::string name = cpuModelName();
  EXPECT_FALSE(name.empty());
  EXPECT_LE(name.size(), kMaxCpuNameBytes);
}

}  // namespace
}  // namespace prism
