// `prism view` end to end: the real executable, under the offscreen platform, alone and with
// 2 MPI ranks.
#include "gui/Viewer.h"

#include <gtest/gtest.h>

#include <regex>

#include "image/ImageIo.h"
#include "master/PrismProcess.h"  // tests/master/

namespace prism {
namespace {

using test::runPrism;
using test::runPrismMpi;

class Viewer : public test::ScratchFolderTest {};

const std::string kScene = PRISM_SOURCE_DIR "/scenes/default.yaml";

void expectSameImage(const std::string& a, const std::string& b) {
  const ImageRgb x = readImage(a);
  const ImageRgb y = readImage(b);
  ASSERT_EQ(x.width, y.width);
  ASSERT_EQ(x.height, y.height);
  size_t different = 0;
  for (size_t i = 0; i < x.pixels.size(); ++i) different += x.pixels[i] != y.pixels[i];
  EXPECT_EQ(different, 0u);
}

TEST_F(Viewer, TwoRanksUnderOffscreenRenderTheSameImageAsRender) {
  ::setenv("QT_QPA_PLATFORM", "offscreen", 1);
  const std::string size = " --width 96 --height 54 --spp 2";
  const auto view =
      runPrismMpi(2, "view " + kScene + size + " --exit-after-passes 1 --save " + path("view.exr"));
  ASSERT_EQ(view.exitCode, 0) << view.output;
  // The slave rendered part of it.
  const auto at = view.output.find("rank 1 ");
  ASSERT_NE(at, std::string::npos) << view.output;
  const auto tiles = std::stoi(view.output.substr(view.output.find("threads, ", at) + 9));
  EXPECT_GT(tiles, 0) << view.output;
  const auto render = runPrism("render " + kScene + size + " -q -o " + path("render.exr"));
  ASSERT_EQ(render.exitCode, 0) << render.output;
  expectSameImage(path("view.exr"), path("render.exr"));
}

TEST_F(Viewer, TwoRanksRenderPhotonMappedPassesLikeOne) {
  ::setenv("QT_QPA_PLATFORM", "offscreen", 1);
  const std::string scene = PRISM_SOURCE_DIR "/tests/data/scenes/caustic-small.yaml";
  const std::string args = " --max-passes 2 --exit-after-passes 2 --photons 8000 --save ";
  const auto two = runPrismMpi(2, "view " + scene + args + path("two.exr"));
  ASSERT_EQ(two.exitCode, 0) << two.output;
  // Rank 1 took part (its Ready gave its threads). How many tiles it rendered depends on timing:
  // on a loaded machine rank 0 may render them all while rank 1 builds its photon kd-tree.
  const auto at = two.output.find("rank 1 ");
  ASSERT_NE(at, std::string::npos) << two.output;
  EXPECT_GT(std::stoi(two.output.substr(at + 7)), 0) << two.output;
  // The photon maps do not depend on the rank count, nor do the tiles: the same average.
  const auto one = runPrism("view " + scene + args + path("one.exr"));
  ASSERT_EQ(one.exitCode, 0) << one.output;
  expectSameImage(path("two.exr"), path("one.exr"));
  // Photon mapped, 2 passes of the --photons budget, and an image unlike --caustics none (where
  // shadow rays see through the glass instead).
  EXPECT_NE(two.output.find("photons    2 passes of 8000, the last: "), std::string::npos)
      << two.output;
  const auto none = runPrism("view " + scene + args + path("none.exr") + " --caustics none");
  ASSERT_EQ(none.exitCode, 0) << none.output;
  EXPECT_EQ(none.output.find("photons "), std::string::npos) << none.output;
  const ImageRgb with = readImage(path("one.exr"));
  const ImageRgb without = readImage(path("none.exr"));
  size_t different = 0;
  for (size_t i = 0; i < with.pixels.size(); ++i) {
    different += glm::length(with.pixels[i] - without.pixels[i]) > 0.05f;
  }
  // 1 % of the pixels (measured 15 of 1200: each photon spreads over its own k-NN radius, narrow
  // at the focus; one wide radius for all would smear the caustic over more of them).
  EXPECT_GT(different, with.pixels.size() / 100);
}

// Caustic mapping in the viewer: each rank builds the maps from the scene, so two ranks give the
// pixels of one, which are `prism render --caustics map`'s (pass 1 keeps the scene's seed).
TEST_F(Viewer, TwoRanksRenderCausticMapsLikeRender) {
  ::setenv("QT_QPA_PLATFORM", "offscreen", 1);
  const std::string scene = PRISM_SOURCE_DIR "/tests/data/scenes/caustic-small.yaml";
  const std::string args =
      " --caustics map --map-resolution 128 --max-passes 1 "
      "--exit-after-passes 1 --save ";
  const auto two = runPrismMpi(2, "view " + scene + args + path("two.exr"));
  ASSERT_EQ(two.exitCode, 0) << two.output;
  EXPECT_NE(two.output.find("caustic map 128x128 x 1 view(s), blur on, built on rank 0 in "),
            std::string::npos)
      << two.output;
  const auto render = runPrism("render " + scene + " --caustics map --map-resolution 128 -q -o " +
                               path("render.exr"));
  ASSERT_EQ(render.exitCode, 0) << render.output;
  expectSameImage(path("two.exr"), path("render.exr"));
}

// The move benchmark: the one line for scripts, exactly, and the lines after it. The camera
// rests between moves, so views get refinement passes too (they are frames while moving, but
// not a move's latency).
TEST_F(Viewer, TheMoveBenchmarkPrintsItsLineForScripts) {
  ::setenv("QT_QPA_PLATFORM", "offscreen", 1);
  const auto run = runPrism("view " + kScene +
                            " --width 96 --height 54 --benchmark-moves 6 --benchmark-interval 150");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const std::regex line(
      R"re((^|\n)realtime  [0-9.]+ frames/s at 96x54, frame time median [0-9.]+ ms, )re"
      R"re(p95 [0-9.]+ ms, [0-9]+ frames at full resolution, ([0-9.]+) Mrays/s\n)re");
  std::smatch found;
  ASSERT_TRUE(std::regex_search(run.output, found, line)) << run.output;
  EXPECT_GT(std::stod(found[2].str()), 0.0) << run.output;  // rays were traced while moving
  EXPECT_NE(run.output.find("benchmark  6 camera moves, one every 150 ms"), std::string::npos)
      << run.output;
  const std::regex latency(R"re(\nlatency    median [0-9.e+-]+ ms, p95 [0-9.e+-]+ ms )re"
                           R"re(\(a move to the first frame showing it\)\n)re");
  EXPECT_TRUE(std::regex_search(run.output, latency)) << run.output;
  EXPECT_NE(run.output.find("\nfull res   "), std::string::npos) << run.output;
}

TEST_F(Viewer, NoDisplayIsAClearError) {
  const auto bare = test::runCommand("env -u DISPLAY -u WAYLAND_DISPLAY -u QT_QPA_PLATFORM " +
                                     std::string(PRISM_EXECUTABLE) + " view " + kScene);
  EXPECT_EQ(bare.exitCode, 1);
  EXPECT_NE(bare.output.find("prism: error: no display"), std::string::npos) << bare.output;
}

TEST_F(Viewer, BadSceneAndBadCsvAreClearErrors) {
  ::setenv("QT_QPA_PLATFORM", "offscreen", 1);
  const auto missing = runPrism("view " + path("nope.yaml"));
  EXPECT_EQ(missing.exitCode, 1);
  EXPECT_NE(missing.output.find("prism: error:"), std::string::npos) << missing.output;
  const auto badSave = runPrism("view " + kScene + " --save " + path("x.bmpx"));
  EXPECT_EQ(badSave.exitCode, 1);
  EXPECT_NE(badSave.output.find("prism: error:"), std::string::npos) << badSave.output;
}

}  // namespace
}  // namespace prism
