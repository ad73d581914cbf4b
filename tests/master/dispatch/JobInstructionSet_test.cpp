#include "master/dispatch/JobInstructionSet.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "transport/LoopbackTransport.h"
#include "wire/Messages.h"

namespace prism {
namespace {

constexpr InstructionSetMask kUpToV2 =
    maskOf(InstructionSet::Baseline) | maskOf(InstructionSet::V2);
constexpr InstructionSetMask kUpToV4 =
    kUpToV2 | maskOf(InstructionSet::V3) | maskOf(InstructionSet::V4);

void hello(LoopbackNetwork& network, int rank, InstructionSetMask sets, const std::string& cpu) {
  network.endpoint(rank).send(0, wire::encode(wire::HelloMessage{sets, cpu}));
}

std::string errorOf(Transport& rank0, InstructionSet requested, double timeout = 5.0) {
  try {
    chooseJobInstructionSet(&rank0, requested, timeout);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "no error";
}

TEST(JobInstructionSet, OneProcessTakesItsOwnBest) {
  const JobInstructionSet job = chooseJobInstructionSet(nullptr, InstructionSet::Auto, 1.0);
  EXPECT_EQ(job.chosen, bestInstructionSet(runnableInstructionSets()));
  EXPECT_EQ(job.limitingRank, -1);
  EXPECT_EQ(job.describe(),
            std::string(instructionSetName(job.chosen)) + " (the best this CPU runs)");
}

// The slave on the oldest CPU holds the whole job to what it runs, and the summary names it.
TEST(JobInstructionSet, TheSlowestRankHoldsTheJobToItsBest) {
  if (!(runnableInstructionSets() & maskOf(InstructionSet::V3))) GTEST_SKIP() << "needs v3";
  LoopbackNetwork network(4);
  hello(network, 3, kUpToV4, "Fast CPU");
  hello(network, 1, kUpToV4, "Fast CPU");
  hello(network, 2, kUpToV2, "Old CPU");
  const JobInstructionSet job =
      chooseJobInstructionSet(&network.endpoint(0), InstructionSet::Auto, 5.0);
  EXPECT_EQ(job.chosen, InstructionSet::V2);
  EXPECT_EQ(job.limitingRank, 2);
  EXPECT_EQ(job.describe(), "x86-64-v2 (rank 2 runs no more: Old CPU)");
}

TEST(JobInstructionSet, EveryRankRunningMoreLeavesRankZerosBest) {
  LoopbackNetwork network(2);
  hello(network, 1, kUpToV4, "Fast CPU");
  const JobInstructionSet job =
      chooseJobInstructionSet(&network.endpoint(0), InstructionSet::Auto, 5.0);
  EXPECT_EQ(job.chosen, bestInstructionSet(runnableInstructionSets()));
  EXPECT_EQ(job.limitingRank, -1);
  EXPECT_EQ(job.describe(),
            std::string(instructionSetName(job.chosen)) + " (the best every rank runs)");
}

TEST(JobInstructionSet, AForcedSetIsKeptOrRefusedNamingTheRankThatLacksIt) {
  {
    LoopbackNetwork network(3);
    hello(network, 1, kUpToV4, "Fast CPU");
    hello(network, 2, kUpToV2, "Old CPU");
    const JobInstructionSet job =
        chooseJobInstructionSet(&network.endpoint(0), InstructionSet::Baseline, 5.0);
    EXPECT_EQ(job.chosen, InstructionSet::Baseline);
    EXPECT_EQ(job.describe(), "x86-64 (--isa)");
  }
  if (!(runnableInstructionSets() & maskOf(InstructionSet::V3))) return;
  LoopbackNetwork network(3);
  hello(network, 1, kUpToV4, "Fast CPU");
  hello(network, 2, kUpToV2, "Old CPU");
  EXPECT_EQ(errorOf(network.endpoint(0), InstructionSet::V3),
            "--isa x86-64-v3: rank 2 (Old CPU) runs at most x86-64-v2");
}

TEST(JobInstructionSet, ASlaveThatFailsOrSpeaksOutOfTurnEndsTheJobByName) {
  {
    LoopbackNetwork network(3);
    hello(network, 1, kUpToV2, "CPU");
    network.endpoint(2).send(0, wire::encode(wire::ErrorMessage{"PRISM_TEST_CPU_LIMIT: bad"}));
    EXPECT_EQ(errorOf(network.endpoint(0), InstructionSet::Auto),
              "rank 2: PRISM_TEST_CPU_LIMIT: bad");
  }
  {
    LoopbackNetwork network(2);
    network.endpoint(1).send(0, wire::encode(wire::ReadyMessage{0.1, 1}));
    EXPECT_EQ(errorOf(network.endpoint(0), InstructionSet::Auto), "rank 1 sent Ready before Hello");
  }
  {
    LoopbackNetwork network(3);
    hello(network, 2, kUpToV2, "CPU");
    EXPECT_EQ(errorOf(network.endpoint(0), InstructionSet::Auto, 0.2),
              "rank 1 did not say which CPU it has");
  }
}

// A Hello the wire cannot vouch for (no baseline, unknown sets, a name past the bound) is
// refused by its decoder, before rank 0 reads it.
TEST(JobInstructionSet, MalformedHellosAreRefusedByTheWire) {
  const auto decodeBack = [](const wire::HelloMessage& m) {
    return wire::decode<wire::HelloMessage>(wire::decodeMessage(wire::encode(m)));
  };
  EXPECT_THROW(decodeBack({maskOf(InstructionSet::V2), "CPU"}), wire::WireError);
  EXPECT_THROW(decodeBack({kUpToV4 | 0x100u, "CPU"}), wire::WireError);
  EXPECT_THROW(decodeBack({kUpToV2, std::string(kMaxCpuNameBytes + 1, 'x')}), wire::WireError);
  EXPECT_EQ(decodeBack({kUpToV2, "CPU"}).instructionSets, kUpToV2);
}

}  // namespace
}  // namespace prism
