// MPI integration tests: `mpiexec -n N prism render` must write exactly the pixels of the
// single-process render, for every rank count, both schedules and two tile sizes, and survive a
// slave that hangs, drops tiles or dies. The fault tests use the static schedule: the faulty
// slave then certainly holds tiles (with the dynamic one, rank 0 may finish a small frame before
// a slave has even built its scene).
#include <gtest/gtest.h>

#include <cstring>
#include <tuple>

#include "PrismProcess.h"
#include "image/ImageIo.h"

namespace prism {
namespace {

// The default scene (mesh from an OBJ file, glass, mirror, checker, cube map), small and quick.
const std::string kScene =
    std::string(PRISM_SOURCE_DIR) + "/scenes/default.yaml -W 96 -H 54 --spp 2";

bool samePixels(const ImageRgb& a, const ImageRgb& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Color)) == 0;
}

class DistributedRender : public test::ScratchFolderTest {
 protected:
  ImageRgb singleProcessReference() {
    const test::ProcessRun run =
        test::runPrism("render " + kScene + " -q -o " + path("reference.exr"));
    EXPECT_EQ(run.exitCode, 0) << run.output;
    return readImage(path("reference.exr"));
  }
};

class DistributedRenderMatrix
    : public DistributedRender,
      public ::testing::WithParamInterface<std::tuple<int, const char*, int>> {};

TEST_P(DistributedRenderMatrix, PixelsAreBitIdenticalToTheSingleProcessRender) {
  const auto [ranks, schedule, tileSize] = GetParam();
  const ImageRgb reference = singleProcessReference();
  const test::ProcessRun run =
      test::runPrismMpi(ranks, "render " + kScene + " -o " + path("mpi.exr") + " --schedule " +
                                   schedule + " --tile-size " + std::to_string(tileSize));
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_TRUE(samePixels(readImage(path("mpi.exr")), reference)) << run.output;
  if (ranks > 1) {
    EXPECT_NE(run.output.find("ranks     " + std::to_string(ranks)), std::string::npos)
        << run.output;
  }
}

INSTANTIATE_TEST_SUITE_P(RanksSchedulesTiles, DistributedRenderMatrix,
                         ::testing::Combine(::testing::Values(1, 2, 3, 4),
                                            ::testing::Values("dynamic", "static"),
                                            ::testing::Values(16, 37)),
                         [](const auto& info) {
                           return "ranks" + std::to_string(std::get<0>(info.param)) + "_" +
                                  std::get<1>(info.param) + "_tile" +
                                  std::to_string(std::get<2>(info.param));
                         });

TEST_F(DistributedRender, HungSlaveIsRetiredAndTheFrameCompletesWithTheSamePixels) {
  const ImageRgb reference = singleProcessReference();
  const test::ProcessRun run = test::runPrismMpi(
      3, "render " + kScene + " -o " + path("hang.exr") +
             " --tile-size 8 --schedule static --lease-timeout 1 --inject-fault hang:2");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_TRUE(samePixels(readImage(path("hang.exr")), reference));
  EXPECT_NE(run.output.find("rank 2:"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("STOPPED ANSWERING"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("re-issued"), std::string::npos) << run.output;
}

// A live slave that loses tiles keeps working; its heartbeat shows which tiles it no longer
// holds, and those are re-issued at once instead of waiting for a lease to run out.
TEST_F(DistributedRender, TilesLostByALiveSlaveAreReissuedAndTheFrameCompletes) {
  const ImageRgb reference = singleProcessReference();
  const test::ProcessRun run =
      test::runPrismMpi(3, "render " + kScene + " -o " + path("drop.exr") +
                               " --tile-size 8 --schedule static --inject-fault drop:1");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_TRUE(samePixels(readImage(path("drop.exr")), reference));
  const size_t rank1 = run.output.find("rank 1:");
  ASSERT_NE(rank1, std::string::npos) << run.output;
  const std::string line = run.output.substr(rank1, run.output.find('\n', rank1) - rank1);
  EXPECT_NE(line.find("lost"), std::string::npos) << run.output;
  EXPECT_EQ(line.find("STOPPED ANSWERING"), std::string::npos) << run.output;
}

// Open MPI 4.1 has no ULFM: by default the death of any rank aborts the whole job. With
// `mpirun --enable-recovery` the others live on, and the master re-issues the dead slave's tiles.
TEST_F(DistributedRender, CrashedSlaveUnderEnableRecoveryIsRetiredAndTheFrameCompletes) {
  const ImageRgb reference = singleProcessReference();
  const test::ProcessRun run = test::runPrismMpi(
      3,
      "render " + kScene + " -o " + path("crash.exr") +
          " --tile-size 8 --schedule static --lease-timeout 1 --inject-fault crash:2",
      "--enable-recovery");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_TRUE(samePixels(readImage(path("crash.exr")), reference));
  EXPECT_NE(run.output.find("STOPPED ANSWERING"), std::string::npos) << run.output;
}

TEST_F(DistributedRender, CrashedSlaveWithoutRecoveryEndsTheJobPromptly) {
  const test::ProcessRun run =
      test::runPrismMpi(3, "render " + kScene + " -o " + path("crash.png") +
                               " --schedule static --inject-fault crash:1");
  EXPECT_NE(run.exitCode, 0) << run.output;
  EXPECT_NE(run.exitCode, 124) << "timed out:\n" << run.output;  // `timeout` exit code
  EXPECT_FALSE(std::filesystem::exists(path("crash.png")));
}

TEST_F(DistributedRender, BadSceneEndsEveryRankWithOneErrorFromRankZero) {
  const std::string scene = path("bad.yaml");
  FILE* f = std::fopen(scene.c_str(), "w");
  std::fputs("objects:\n  - sphere: {center: [0, 0, 0], radius: -1}\n", f);
  std::fclose(f);
  const test::ProcessRun run = test::runPrismMpi(3, "render " + scene + " -o " + path("o.png"));
  EXPECT_NE(run.exitCode, 0);
  const std::string message = "bad.yaml:2:";
  const size_t first = run.output.find(message);
  ASSERT_NE(first, std::string::npos) << run.output;
  EXPECT_EQ(run.output.find(message, first + 1), std::string::npos) << "reported twice:\n"
                                                                    << run.output;
  EXPECT_FALSE(std::filesystem::exists(path("o.png")));
}

TEST_F(DistributedRender, BadOptionIsReportedOnceNotByEveryRank) {
  const test::ProcessRun run =
      test::runPrismMpi(3, "render " + kScene + " --schedule sideways -o " + path("o.png"));
  EXPECT_NE(run.exitCode, 0);
  const size_t first = run.output.find("sideways");
  ASSERT_NE(first, std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("--schedule", run.output.find("\n", first)), std::string::npos)
      << run.output;
}

// ---- caustics -------------------------------------------------------------------------------

// Photons are traced across the ranks (each its share of the photon indices, from per-photon
// streams) and the map is sent to every slave, so the caustic image must be bit-identical to
// the single-process one for any rank count, in classic and in progressive mode.
const std::string kCausticScene = std::string(PRISM_TEST_DATA_DIR) + "/scenes/caustic-small.yaml";

class DistributedCaustics : public DistributedRender,
                            public ::testing::WithParamInterface<std::tuple<int, const char*>> {};

TEST_P(DistributedCaustics, PixelsAreBitIdenticalToTheSingleProcessRender) {
  const auto [ranks, mode] = GetParam();
  const std::string scene = kCausticScene + " " + mode;
  const test::ProcessRun single =
      test::runPrism("render " + scene + " -q -o " + path("reference.exr"));
  ASSERT_EQ(single.exitCode, 0) << single.output;
  const test::ProcessRun run =
      test::runPrismMpi(ranks, "render " + scene + " -o " + path("mpi.exr") + " --tile-size 8");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_TRUE(samePixels(readImage(path("mpi.exr")), readImage(path("reference.exr"))))
      << run.output;
  EXPECT_NE(run.output.find("caustics  photon map"), std::string::npos) << run.output;
  if (ranks > 1) {
    EXPECT_NE(run.output.find("photons traced by rank"), std::string::npos) << run.output;
  }
}

// A slave that hangs never sends its photon share: after the lease rank 0 retires it, traces
// its share itself, and the frames go on without it. The photons are the same, so the pixels
// are too.
TEST_F(DistributedRender, HungSlavesPhotonShareIsTracedByRankZeroWithTheSamePixels) {
  const std::string scene = kCausticScene + " --progressive --passes 2";
  const test::ProcessRun single =
      test::runPrism("render " + scene + " -q -o " + path("reference.exr"));
  ASSERT_EQ(single.exitCode, 0) << single.output;
  const test::ProcessRun run =
      test::runPrismMpi(3, "render " + scene + " -o " + path("hang.exr") +
                               " --tile-size 8 --lease-timeout 1 --inject-fault hang:2");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_TRUE(samePixels(readImage(path("hang.exr")), readImage(path("reference.exr"))))
      << run.output;
  EXPECT_NE(run.output.find("STOPPED ANSWERING"), std::string::npos) << run.output;
  // Rank 2 traced nothing; ranks 0 and 1 traced every photon of both passes between them.
  EXPECT_NE(run.output.find(", 2: 0\n"), std::string::npos) << run.output;
}

// Caustic mapping: every rank builds the maps itself from the scene; the image must not depend
// on how many ranks did.
TEST_F(DistributedRender, CausticMapPixelsAreBitIdenticalForOneAndTwoRanks) {
  const std::string scene = kCausticScene + " --caustics caustic-map --map-resolution 128";
  const test::ProcessRun single =
      test::runPrism("render " + scene + " -q -o " + path("reference.exr"));
  ASSERT_EQ(single.exitCode, 0) << single.output;
  const test::ProcessRun run =
      test::runPrismMpi(2, "render " + scene + " -o " + path("mpi.exr") + " --tile-size 8");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_TRUE(samePixels(readImage(path("mpi.exr")), readImage(path("reference.exr"))))
      << run.output;
  EXPECT_NE(run.output.find("caustics  caustic map: 128x128"), std::string::npos) << run.output;
}

// Progressive with per-photon radii (the default) and with the one fixed radius of a scene that
// sets it.
INSTANTIATE_TEST_SUITE_P(RanksModes, DistributedCaustics,
                         ::testing::Combine(::testing::Values(1, 2, 3),
                                            ::testing::Values("", "--progressive --passes 3",
                                                              "--progressive --passes 3 "
                                                              "--gather-radius 0.05")),
                         [](const auto& info) {
                           const std::string mode = std::get<1>(info.param);
                           return "ranks" + std::to_string(std::get<0>(info.param)) +
                                  (mode.empty()                               ? "_classic"
                                   : mode.find("radius") != std::string::npos ? "_fixed_radius"
                                                                              : "_progressive");
                         });

}  // namespace
}  // namespace prism
