// MPI integration tests: `mpiexec -n N prism render` must write exactly the pixels of the
// single-process render, for every rank count, both schedules and two tile sizes, and survive a
// slave that hangs, drops tiles or dies. The fault tests use the static schedule: the faulty
// slave then certainly holds tiles (with the dynamic one, rank 0 may finish a small frame before
// a slave has even built its scene).
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <regex>
#include <tuple>

#include "PrismProcess.h"
#include "SamePixels.h"
#include "image/ImageIo.h"

namespace prism {
namespace {

// The default scene (mesh from an OBJ file, glass, mirror, checker, cube map), small and quick.
const std::string kScene =
    std::string(PRISM_SOURCE_DIR) + "/scenes/default.yaml -W 96 -H 54 --spp 2";

using test::samePixels;

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

// ---- between nodes: Open MPI over TCP -------------------------------------------------------

// Between nodes Prism's messages cross a network. Forcing Open MPI's TCP transport on one node
// (btl tcp and self only, so no shared memory; pml ob1, or UCX would carry the messages instead)
// sends them through sockets as between machines (the tcp btl skips loopback and uses the real
// interface). The verbose btl output shows TCP was really initialised.
// Held while an MPI job that loses a rank on purpose runs: two such jobs at once on one machine
// (ctest -j) left the one over TCP hung until the 120 s timeout in 1 of 2 concurrent runs, and
// it still hung now and then beside other MPI jobs. Stacks of a hung run showed how: rank 0 had
// ended (MPI_Abort, which under --enable-recovery did not kill the other slave) and the surviving
// slave, which never received the shutdown, waited for rank 0 with its sends stuck in Open MPI.
// Slaves now notice a gone rank 0 by its doorbell (InterruptedRender.SlavesEndOnTheirOwn...); the
// lock stays, as two jobs that kill ranks at once are not what these tests are about. An flock,
// so it also holds across the test processes ctest runs in parallel.
class CrashedJobLock {
 public:
  CrashedJobLock() {
    const std::string file =
        (std::filesystem::temp_directory_path() / "prism-tests-crashed-rank.lock").string();
    fd_ = ::open(file.c_str(), O_CREAT | O_RDWR, 0666);
    if (fd_ >= 0) ::flock(fd_, LOCK_EX);
  }
  ~CrashedJobLock() {
    if (fd_ >= 0) ::close(fd_);  // releases the lock
  }
  CrashedJobLock(const CrashedJobLock&) = delete;
  CrashedJobLock& operator=(const CrashedJobLock&) = delete;

 private:
  int fd_ = -1;
};

const std::string kOverTcp = "--mca pml ob1 --mca btl tcp,self --mca btl_base_verbose 30";

bool tcpTransportWasUsed(const std::string& output) {
  return output.find("select: init of component tcp returned success") != std::string::npos &&
         output.find("component vader") == std::string::npos;
}

class DistributedRenderOverTcp
    : public DistributedRender,
      public ::testing::WithParamInterface<std::tuple<int, const char*>> {};

TEST_P(DistributedRenderOverTcp, PixelsAreBitIdenticalToTheSingleProcessRender) {
  const auto [ranks, schedule] = GetParam();
  const ImageRgb reference = singleProcessReference();
  const test::ProcessRun run = test::runPrismMpi(
      ranks,
      "render " + kScene + " -o " + path("tcp.exr") + " --tile-size 8 --schedule " + schedule,
      kOverTcp);
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_TRUE(samePixels(readImage(path("tcp.exr")), reference)) << run.output;
  EXPECT_TRUE(tcpTransportWasUsed(run.output)) << run.output;
  EXPECT_NE(run.output.find("ranks     " + std::to_string(ranks)), std::string::npos) << run.output;
}

INSTANTIATE_TEST_SUITE_P(RanksSchedules, DistributedRenderOverTcp,
                         ::testing::Combine(::testing::Values(2, 3),
                                            ::testing::Values("dynamic", "static")),
                         [](const auto& info) {
                           return "ranks" + std::to_string(std::get<0>(info.param)) + "_" +
                                  std::get<1>(info.param);
                         });

// Rank 0's geometry broadcast, forced on and off, over shared memory and over TCP: the pixels of
// one process either way (the build is deterministic), and the summary says which ran.
TEST_F(DistributedRender, TheGeometryBroadcastOrBuiltOnEveryRankGivesTheSamePixels) {
  const ImageRgb reference = singleProcessReference();
  for (const std::string& link : {std::string(), kOverTcp}) {
    for (const auto& [mode, said] :
         {std::pair<std::string, std::string>{"broadcast", "geometry broadcast by rank 0"},
          {"local", "geometry built on every rank (local)"},
          {"auto", " (auto: predicted "}}) {
      const std::string image = path(mode + (link.empty() ? "-shm" : "-tcp") + ".exr");
      const test::ProcessRun run =
          test::runPrismMpi(3, "render " + kScene + " -o " + image + " --bvh-share " + mode, link);
      ASSERT_EQ(run.exitCode, 0) << run.output;
      EXPECT_TRUE(samePixels(readImage(image), reference)) << mode << run.output;
      EXPECT_NE(run.output.find(said), std::string::npos) << run.output;
      EXPECT_NE(run.output.find(", first tile at "), std::string::npos) << run.output;
    }
  }
}

// Models as users bring them: an OBJ with its MTL and PNG textures placed by a scene, and a glTF
// binary rendered as a scene of its own. Textures and materials travel in the broadcast (a slave
// reads no file), and three ranks give the pixels of one process.
TEST_F(DistributedRender, TexturedModelsGiveTheSamePixelsOnThreeRanks) {
  for (const std::string model : {"textured-still-life.yaml", "globe.glb"}) {
    const std::string scene =
        std::string(PRISM_SOURCE_DIR) + "/scenes/" + model + " -W 96 -H 54 --spp 2 --photons 20000";
    const test::ProcessRun single =
        test::runPrism("render " + scene + " -q -o " + path("one.exr") + " --overwrite");
    ASSERT_EQ(single.exitCode, 0) << single.output;
    const test::ProcessRun three =
        test::runPrismMpi(3, "render " + scene + " -o " + path("three.exr") + " --overwrite");
    ASSERT_EQ(three.exitCode, 0) << three.output;
    EXPECT_TRUE(samePixels(readImage(path("three.exr")), readImage(path("one.exr")))) << model;
  }
}

// A slave that dies breaks its TCP connections (the other ranks see a reset, not a silent
// shared-memory segment): under --enable-recovery the master must still retire it and finish.
TEST_F(DistributedRender, OverTcpACrashedSlaveUnderEnableRecoveryIsRetiredWithTheSamePixels) {
  const CrashedJobLock alone;
  const ImageRgb reference = singleProcessReference();
  const test::ProcessRun run = test::runPrismMpi(
      3,
      "render " + kScene + " -o " + path("crash.exr") +
          " --tile-size 8 --schedule static --lease-timeout 1 --inject-fault crash:2",
      kOverTcp + " --enable-recovery");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_TRUE(samePixels(readImage(path("crash.exr")), reference));
  EXPECT_TRUE(tcpTransportWasUsed(run.output)) << run.output;
  EXPECT_NE(run.output.find("STOPPED ANSWERING"), std::string::npos) << run.output;
}

// On one machine with no layer chosen, MpiSession names ob1 before MPI_Init, so Open MPI
// neither opens nor probes UCX (docs/distributed.md: about 0.2 s of every job's start).
TEST_F(DistributedRender, OnOneMachineOb1IsChosenWithoutProbingOtherLayers) {
  const test::ProcessRun run = test::runPrismMpi(2, "render " + kScene + " -o " + path("ob1.exr"),
                                                 "--mca pml_base_verbose 10");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("select: component ob1 selected"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("pml component ucx"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("pml component cm"), std::string::npos) << run.output;
}

// A layer the user names wins over that choice (here UCX, whether or not it can start).
TEST_F(DistributedRender, ALayerTheUserNamesIsNotOverridden) {
  const test::ProcessRun run = test::runPrismMpi(2, "render " + kScene + " -o " + path("ucx.exr"),
                                                 "--mca pml_base_verbose 10 --mca pml ucx");
  EXPECT_NE(run.output.find("initializing pml component ucx"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("initializing pml component ob1"), std::string::npos) << run.output;
}

// ---- uneven nodes: ranks with different thread counts and speeds ---------------------------

struct RankLine {
  int threads = -1;
  int tiles = -1;
};

// "  rank 2: 3 threads, 80 tiles, ..." from the run summary.
RankLine rankLine(const std::string& output, int rank) {
  RankLine line;
  const std::string key = "  rank " + std::to_string(rank) + ": ";
  const size_t at = output.find(key);
  if (at != std::string::npos) {
    std::sscanf(output.c_str() + at + key.size(), "%d threads, %d tiles", &line.threads,
                &line.tiles);
  }
  return line;
}

class UnevenRanks : public DistributedRender {
 protected:
  ImageRgb reference(const std::string& scene) {
    const test::ProcessRun run =
        test::runPrism("render " + scene + " -q -o " + path("reference.exr"));
    EXPECT_EQ(run.exitCode, 0) << run.output;
    return readImage(path("reference.exr"));
  }
  // One MPI job of three ranks, each with the common arguments and then its own (MPMD).
  test::ProcessRun render(const std::string& common, const std::string& rank0,
                          const std::string& rank1, const std::string& rank2) {
    const std::string all = "render " + common + " --overwrite -o " + path("uneven.exr") + " ";
    return test::runPrismMpmd({all + rank0, all + rank1, all + rank2}, "--bind-to none");
  }
};

// Every rank reads its own command line: each renders with the threads it was given, and rank 0
// does not need the slaves' command lines to match its own.
TEST_F(UnevenRanks, EachRankUsesItsOwnThreadCountAndThePixelsAreBitIdentical) {
  const ImageRgb expected = reference(kScene);
  for (const char* schedule : {"dynamic", "static"}) {
    const test::ProcessRun run = render(kScene + " --tile-size 8 --schedule " + schedule,
                                        "--threads 1", "--threads 3", "--threads 2 -q");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_TRUE(samePixels(readImage(path("uneven.exr")), expected)) << run.output;
    EXPECT_EQ(rankLine(run.output, 0).threads, 1) << run.output;
    EXPECT_EQ(rankLine(run.output, 1).threads, 3) << run.output;
    EXPECT_EQ(rankLine(run.output, 2).threads, 2) << run.output;
  }
}

// Rank 2 is a slow node: every tile holds its thread 0.2 s longer (--inject-fault slow:2), many
// times a tile's render time even with the 2 cores shared, so its pace is known whatever else
// runs. The frame (240 tiles, about 2 s) is long enough that both slaves join while rank 0 still
// renders. The pull queue must give the slow rank under half the tiles of the other slave.
TEST_F(UnevenRanks, TheDynamicQueueGivesASlowRankFewerTiles) {
  const std::string scene =
      std::string(PRISM_SOURCE_DIR) + "/scenes/default.yaml -W 320 -H 180 --spp 48 --tile-size 16";
  const ImageRgb expected = reference(scene);
  const std::string options = "--threads 1 --inject-fault slow:2";
  const test::ProcessRun run = render(scene + " --schedule dynamic", options, options, options);
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_TRUE(samePixels(readImage(path("uneven.exr")), expected)) << run.output;
  const RankLine normal = rankLine(run.output, 1);
  const RankLine slow = rankLine(run.output, 2);
  EXPECT_GT(normal.tiles, 2 * slow.tiles) << run.output;
  EXPECT_GT(slow.tiles, 0) << run.output;  // it took part, only less
}

// The static interleave gives every worker its share whatever its pace: 15 tiles of 64 px, 5
// each, the slow rank's included, and the frame waits for them.
TEST_F(UnevenRanks, TheStaticScheduleGivesASlowRankItsFullShare) {
  const std::string scene =
      std::string(PRISM_SOURCE_DIR) + "/scenes/default.yaml -W 320 -H 180 --tile-size 64";
  const ImageRgb expected = reference(scene);
  const std::string options = "--threads 1 --inject-fault slow:2";
  const test::ProcessRun run = render(scene + " --schedule static", options, options, options);
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_TRUE(samePixels(readImage(path("uneven.exr")), expected)) << run.output;
  for (int rank = 0; rank < 3; ++rank) EXPECT_EQ(rankLine(run.output, rank).tiles, 5) << run.output;
}

// Rank 0 checks the scene against its own memory before the broadcast; a slave on a smaller
// machine checks it again against its own limit before it builds anything, and the job ends
// with its refusal, once, and no image. Rank 0 waits for every slave's answer before it builds,
// so no rank spends a build on a job that will not run: the message says so, and it comes only
// from that wait (a refusal heard after a build would not carry it).
TEST_F(UnevenRanks, ARankWithLessMemoryRefusesTheSceneBeforeBuildingIt) {
  const test::ProcessRun run = render(kScene, "", "--memory-limit 16M", "");
  EXPECT_NE(run.exitCode, 0) << run.output;
  const std::string refusal =
      "rank 1: cannot build the scene: the scene's geometry (9600 triangles) needs 88.2 MiB "
      "(92521720 bytes); the memory limit is 16.0 MiB (16777216 bytes, --memory-limit)";
  const size_t first = run.output.find(refusal);
  ASSERT_NE(first, std::string::npos) << run.output;
  EXPECT_EQ(run.output.find(refusal, first + 1), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("simplify the meshes (before any rank built the scene)", first),
            std::string::npos)
      << run.output;
  EXPECT_FALSE(std::filesystem::exists(path("uneven.exr")));
}

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
  const CrashedJobLock alone;
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
  const CrashedJobLock alone;
  const test::ProcessRun run =
      test::runPrismMpi(3, "render " + kScene + " -o " + path("crash.exr") +
                               " --schedule static --inject-fault crash:1");
  EXPECT_NE(run.exitCode, 0) << run.output;
  EXPECT_NE(run.exitCode, 124) << "timed out:\n" << run.output;  // `timeout` exit code
  // mpirun ends the job; rank 0 may have re-issued the dead slave's tiles and finished the small
  // frame before that (docs/distributed.md). Then the image must be whole and right.
  if (std::filesystem::exists(path("crash.exr"))) {
    EXPECT_TRUE(samePixels(readImage(path("crash.exr")), singleProcessReference())) << run.output;
  }
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

// A photon pass before the frame, with rank 0's geometry broadcast: every slave has it in time
// to trace its share of the photons.
TEST_F(DistributedRender, AGeometryBroadcastBeforeAPhotonPassGivesTheSamePixels) {
  const test::ProcessRun single =
      test::runPrism("render " + kCausticScene + " -q -o " + path("reference.exr"));
  ASSERT_EQ(single.exitCode, 0) << single.output;
  const test::ProcessRun run = test::runPrismMpi(
      3, "render " + kCausticScene + " -o " + path("mpi.exr") + " --bvh-share broadcast");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_TRUE(samePixels(readImage(path("mpi.exr")), readImage(path("reference.exr"))))
      << run.output;
  EXPECT_NE(run.output.find("geometry broadcast by rank 0 (broadcast)"), std::string::npos)
      << run.output;
  // The slaves had the geometry in time for their shares (else rank 0 traces every photon).
  EXPECT_TRUE(std::regex_search(run.output, std::regex("photons traced by rank: 0: [0-9]+, "
                                                       "1: [1-9][0-9]*, 2: [1-9]")))
      << run.output;
}

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
    // The radii were found by every rank, a share each (a fixed radius needs none).
    const bool radii = std::string(mode).find("--gather-radius") == std::string::npos;
    EXPECT_EQ(run.output.find("radii found by rank") != std::string::npos, radii) << run.output;
  }
}

// Under MPI a budget's passes are counted by rank 0 alone: a budget that stops after the first
// pass (set-up takes more than a millisecond; the first pass always runs) gives every rank count
// the pixels of one progressive pass in one process.
TEST_F(DistributedRender, ABudgetsPassesAreTheSameForAnyRankCount) {
  const test::ProcessRun single = test::runPrism(
      "render " + kCausticScene + " --progressive --passes 1 -q -o " + path("one-pass.exr"));
  ASSERT_EQ(single.exitCode, 0) << single.output;
  for (const int ranks : {1, 3}) {
    const std::string image = path("budget" + std::to_string(ranks) + ".exr");
    const test::ProcessRun run = test::runPrismMpi(
        ranks, "render " + kCausticScene + " --time-budget 0.001 --tile-size 8 -o " + image);
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_NE(run.output.find("start to written image: 1 pass; at "), std::string::npos)
        << run.output;
    EXPECT_TRUE(samePixels(readImage(image), readImage(path("one-pass.exr")))) << run.output;
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
  // Rank 2 traced nothing and found no radius; ranks 0 and 1 did all of both passes.
  EXPECT_NE(run.output.find(", 2: 0; radii found by rank:"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find(", 2: 0\n"), std::string::npos) << run.output;
}

// A slave killed during a photon pass (--inject-fault crash-photons:2: it dies when its first
// PhotonJob arrives, as if killed) under `mpirun --enable-recovery`: rank 0 retires it, traces
// its share itself, and renders the frame without it. The photons are the same, so the pixels
// are too. Classic (the photon pass before the only frame) and progressive (the slave has
// rendered the direct pass's tiles and dies at the first caustic pass).
TEST_F(DistributedRender, CrashedSlaveDuringAPhotonPassUnderEnableRecoveryGivesTheSamePixels) {
  const CrashedJobLock alone;
  for (const char* mode : {"", " --progressive --passes 3"}) {
    const std::string scene = kCausticScene + mode;
    const test::ProcessRun single =
        test::runPrism("render " + scene + " -q --overwrite -o " + path("reference.exr"));
    ASSERT_EQ(single.exitCode, 0) << single.output;
    const test::ProcessRun run =
        test::runPrismMpi(3,
                          "render " + scene + " --overwrite -o " + path("crash.exr") +
                              " --tile-size 8 --lease-timeout 1 --inject-fault crash-photons:2",
                          "--enable-recovery");
    ASSERT_EQ(run.exitCode, 0) << mode << "\n" << run.output;
    EXPECT_TRUE(samePixels(readImage(path("crash.exr")), readImage(path("reference.exr"))))
        << mode << "\n"
        << run.output;
    EXPECT_NE(run.output.find("STOPPED ANSWERING"), std::string::npos) << run.output;
    // Rank 2 traced nothing and found no radius: rank 0 did its shares.
    EXPECT_NE(run.output.find(", 2: 0; radii found by rank:"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find(", 2: 0\n"), std::string::npos) << run.output;
  }
}

// Budgets smaller than the ranks: with 2 photons two of three ranks trace none (no job is sent,
// and none is waited for, or the run would wait for them forever), and 40 photons store fewer
// than one chunk of radii (24 of them, as the stratified emission and roulette keep
// them), found by one rank. The pixels are one process's.
TEST_F(DistributedRender, PhotonSharesAndRadiiSharesLeftEmptyAreNotWaitedFor) {
  for (const char* photons : {"2", "40"}) {
    const std::string scene = kCausticScene + " --photons " + photons;
    const test::ProcessRun single =
        test::runPrism("render " + scene + " -q --overwrite -o " + path("reference.exr"));
    ASSERT_EQ(single.exitCode, 0) << single.output;
    const test::ProcessRun run =
        test::runPrismMpi(3, "render " + scene + " --overwrite -o " + path("mpi.exr"));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_TRUE(samePixels(readImage(path("mpi.exr")), readImage(path("reference.exr"))))
        << run.output;
    const std::string shares = std::string(photons) == "2"
                                   ? "photons traced by rank: 0: 0, 1: 0, 2: 2"
                                   : "radii found by rank: 0: 0, 1: 0, 2: 24";
    EXPECT_NE(run.output.find(shares), std::string::npos) << run.output;
  }
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

// gather: auto travels with the photon map: on the ring's fold each photon's own k differs from
// the largest k (so a slave that ignored it would render other pixels), and two ranks give the
// single process's image.
TEST_F(DistributedRender, AutomaticKIsCarriedToTheSlaves) {
  const std::string scene = std::string(PRISM_SOURCE_DIR) +
                            "/scenes/caustic-ring.yaml -W 64 -H 48 --spp 1 --photons 200000";
  const test::ProcessRun fixed =
      test::runPrism("render " + scene + " --gather 400 -q -o " + path("fixed.exr"));
  ASSERT_EQ(fixed.exitCode, 0) << fixed.output;
  const test::ProcessRun single =
      test::runPrism("render " + scene + " --gather-noise 0.05 -q -o " + path("reference.exr"));
  ASSERT_EQ(single.exitCode, 0) << single.output;
  ASSERT_FALSE(samePixels(readImage(path("fixed.exr")), readImage(path("reference.exr"))));
  const test::ProcessRun run = test::runPrismMpi(
      2, "render " + scene + " --gather-noise 0.05 -o " + path("mpi.exr") +
             " --tile-size 8 --schedule static");  // the slave renders half the tiles
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_TRUE(samePixels(readImage(path("mpi.exr")), readImage(path("reference.exr"))))
      << run.output;
  EXPECT_NE(run.output.find("k <= 400, auto"), std::string::npos) << run.output;
}

// Photon shares are gathered and the map sent on to every slave: the largest messages of a
// caustic render, here over TCP.
TEST_F(DistributedRender, OverTcpProgressivePhotonMapPixelsAreBitIdentical) {
  const std::string scene = kCausticScene + " --progressive --passes 3";
  const test::ProcessRun single =
      test::runPrism("render " + scene + " -q -o " + path("reference.exr"));
  ASSERT_EQ(single.exitCode, 0) << single.output;
  const test::ProcessRun run = test::runPrismMpi(
      3, "render " + scene + " -o " + path("tcp.exr") + " --tile-size 8", kOverTcp);
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_TRUE(samePixels(readImage(path("tcp.exr")), readImage(path("reference.exr"))))
      << run.output;
  EXPECT_TRUE(tcpTransportWasUsed(run.output)) << run.output;
  EXPECT_NE(run.output.find("photons traced by rank"), std::string::npos) << run.output;
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
