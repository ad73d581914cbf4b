// One instruction set per job (util/InstructionSet.h, master/dispatch/JobInstructionSet.h), end to
// end: every rank reports what its CPU runs, rank 0 picks the best they all run (or the forced
// one) and every rank renders with it, so a job whose rank runs less gives that set's image, the
// same one process gives. A rank plays an older CPU through PRISM_TEST_CPU_LIMIT.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "PrismProcess.h"
#include "SamePixels.h"
#include "image/ImageError.h"
#include "image/ImageIo.h"
#include "util/InstructionSet.h"

namespace prism {
namespace {

const std::string kScene =
    std::string(PRISM_SOURCE_DIR) + "/scenes/default.yaml -W 96 -H 54 --spp 2";

using test::samePixels;

bool runs(InstructionSet isa) {
  return (runnableInstructionSets() & maskOf(isa)) != 0;
}

class InstructionSets : public test::ScratchFolderTest {
 protected:
  // One MPI job of three ranks in which rank 2's CPU plays one that runs at most `rank2Limit`.
  test::ProcessRun renderWithOlderRank2(const std::string& arguments, const char* rank2Limit) {
    test::prepareMpiEnvironment();
    const std::string prism = std::string(PRISM_EXECUTABLE) + " " + arguments;
    return test::runCommand("timeout 120 mpiexec --oversubscribe -n 2 " + prism +
                            " : -n 1 -x PRISM_TEST_CPU_LIMIT=" + rank2Limit + " " + prism);
  }
  ImageRgb render(const std::string& arguments, const std::string& name, int ranks = 1) {
    const std::string command = "render " + arguments + " --overwrite -o " + path(name);
    const test::ProcessRun run =
        ranks == 1 ? test::runPrism(command) : test::runPrismMpi(ranks, command);
    EXPECT_EQ(run.exitCode, 0) << run.output;
    return readImage(path(name));
  }
};

// Rank 2 runs no more than x86-64-v2: the job runs v2 everywhere, says so, and writes the image
// one process writes with --isa v2.
TEST_F(InstructionSets, ARankOnAnOlderCpuHoldsTheWholeJobToItsSet) {
  if (!runs(InstructionSet::V3)) GTEST_SKIP() << "this CPU runs nothing past x86-64-v2";
  const ImageRgb expected = render(kScene + " -q --isa v2", "v2.exr");
  const test::ProcessRun run =
      renderWithOlderRank2("render " + kScene + " --overwrite -o " + path("job.exr"), "v2");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("kernels   x86-64-v2 (rank 2 runs no more: "), std::string::npos)
      << run.output;
  EXPECT_TRUE(samePixels(readImage(path("job.exr")), expected)) << run.output;
}

// A set forced past what a rank runs ends the job before any rank builds the scene, with one
// message that names the rank; on rank 0 the same as a plain error.
TEST_F(InstructionSets, AForcedSetARankLacksIsRefusedByName) {
  if (!runs(InstructionSet::V3)) GTEST_SKIP() << "this CPU runs nothing past x86-64-v2";
  const test::ProcessRun run = renderWithOlderRank2(
      "render " + kScene + " --isa v3 --overwrite -o " + path("job.exr"), "v2");
  EXPECT_NE(run.exitCode, 0) << run.output;
  const std::string refusal = "prism: error: --isa x86-64-v3: rank 2 (";
  const size_t first = run.output.find(refusal);
  ASSERT_NE(first, std::string::npos) << run.output;
  EXPECT_EQ(run.output.find(refusal, first + 1), std::string::npos) << run.output;
  EXPECT_NE(run.output.find(") runs at most x86-64-v2"), std::string::npos) << run.output;
  EXPECT_FALSE(std::filesystem::exists(path("job.exr")));

  ::setenv("PRISM_TEST_CPU_LIMIT", "v2", 1);
  const test::ProcessRun alone =
      test::runPrism("render " + kScene + " --isa v3 -o " + path("alone.exr"));
  ::unsetenv("PRISM_TEST_CPU_LIMIT");
  EXPECT_NE(alone.exitCode, 0);
  EXPECT_NE(alone.output.find("instruction set x86-64-v3: this CPU runs at most x86-64-v2"),
            std::string::npos)
      << alone.output;
  const test::ProcessRun unknown = test::runPrism("render " + kScene + " --isa avx2");
  EXPECT_NE(unknown.exitCode, 0);
  EXPECT_NE(unknown.output.find("unknown instruction set 'avx2'"), std::string::npos)
      << unknown.output;
}

// Every set this CPU runs gives one image for one process and for three ranks, and the summary
// names the set it ran.
TEST_F(InstructionSets, EachSetGivesOneImageOnOneProcessAndOnThreeRanks) {
  for (InstructionSet isa : instructionSetsIn(runnableInstructionSets())) {
    const std::string name = instructionSetName(isa);
    const ImageRgb one = render(kScene + " -q --isa " + name, name + "-1.exr");
    const test::ProcessRun run = test::runPrismMpi(
        3, "render " + kScene + " --isa " + name + " --overwrite -o " + path(name + "-3.exr"));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_NE(run.output.find("kernels   " + name + " (--isa)"), std::string::npos) << run.output;
    EXPECT_TRUE(samePixels(readImage(path(name + "-3.exr")), one)) << name;
  }
}

// The sets may round differently (pixels may change with a kernel's arithmetic, never within
// a job), but none may be less accurate: against a 256-spp render, each set's 16-spp
// render has the baseline's RMSE within 1 %.
TEST_F(InstructionSets, EverySetIsAsAccurateAsTheBaseline) {
  const std::string scene = std::string(PRISM_SOURCE_DIR) + "/scenes/default.yaml -W 64 -H 36 -q";
  const ImageRgb reference = render(scene + " --spp 256 --isa x86-64", "reference.exr");
  const double baseline =
      imageError(render(scene + " --spp 16 --isa x86-64", "baseline.exr"), reference).rmse;
  ASSERT_GT(baseline, 0.0);
  for (InstructionSet isa : instructionSetsIn(runnableInstructionSets())) {
    const std::string name = instructionSetName(isa);
    const ImageRgb image = render(scene + " --spp 16 --isa " + name, name + ".exr");
    EXPECT_NEAR(imageError(image, reference).rmse, baseline, 0.01 * baseline) << name;
  }
}

}  // namespace
}  // namespace prism
