// Start-up cost: a process loads Qt, MPI and OpenImageIO only when it uses them
// (docs/dependencies.md). The dynamic loader's own trace (LD_DEBUG=files) says which libraries a
// child process opened; the modules' errors name where they were looked for.
#include <gtest/gtest.h>

#include <string>

#include "image/ImageIo.h"
#include "master/PrismProcess.h"

namespace prism {
namespace {

const std::string kScene = std::string(PRISM_SOURCE_DIR) + "/scenes/lambert-plane.yaml";

class LazyLibraries : public test::ScratchFolderTest {
 protected:
  // The libraries the dynamic loader opened for `prism arguments`, one "file=..." line each.
  test::ProcessRun loaderTrace(const std::string& arguments) {
    return test::runCommand("LD_DEBUG=files " + std::string(PRISM_EXECUTABLE) + " " + arguments);
  }
  static bool opened(const test::ProcessRun& run, const std::string& library) {
    return run.output.find("file=" + library) != std::string::npos;
  }
};

TEST_F(LazyLibraries, ARenderToPngAndExrOpensNeitherQtNorMpiNorOpenImageIo) {
  for (const char* file : {"x.png", "x.exr"}) {
    const test::ProcessRun run = loaderTrace("render " + kScene + " -W 8 -H 8 -q -o " + path(file));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    ASSERT_TRUE(opened(run, "libpng")) << "the trace names no library:\n" << run.output;
    EXPECT_FALSE(opened(run, "libQt5")) << file;
    EXPECT_FALSE(opened(run, "libmpi")) << file;
    EXPECT_FALSE(opened(run, "libOpenImageIO")) << file;
    EXPECT_FALSE(opened(run, "prism_viewer.so")) << file;
    EXPECT_FALSE(opened(run, "prism_mpi.so")) << file;
  }
}

TEST_F(LazyLibraries, VersionOpensNoneOfTheLargeLibraries) {
  const test::ProcessRun run = loaderTrace("--version");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("prism "), std::string::npos) << run.output;
  EXPECT_FALSE(opened(run, "libQt5")) << run.output;
  EXPECT_FALSE(opened(run, "libmpi")) << run.output;
  EXPECT_FALSE(opened(run, "libOpenImageIO")) << run.output;
}

TEST_F(LazyLibraries, UnderALauncherEveryRankLoadsMpiAndRendersTheSamePixels) {
  const test::ProcessRun alone =
      test::runPrism("render " + kScene + " -W 16 -H 16 -q -o " + path("one.exr"));
  ASSERT_EQ(alone.exitCode, 0) << alone.output;
  ::setenv("LD_DEBUG", "files", 1);
  const test::ProcessRun ranks =
      test::runPrismMpi(2, "render " + kScene + " -W 16 -H 16 -q -o " + path("two.exr"));
  ::unsetenv("LD_DEBUG");
  ASSERT_EQ(ranks.exitCode, 0) << ranks.output;
  EXPECT_TRUE(opened(ranks, "libmpi")) << ranks.output;
  EXPECT_FALSE(opened(ranks, "libQt5"));
  const ImageRgb one = readImage(path("one.exr"));
  const ImageRgb two = readImage(path("two.exr"));
  ASSERT_EQ(one.pixels.size(), two.pixels.size());
  for (size_t i = 0; i < one.pixels.size(); ++i) ASSERT_EQ(one.pixels[i], two.pixels[i]) << i;
}

TEST_F(LazyLibraries, AMissingMpiModuleUnderALauncherIsAClearError) {
  ::setenv("PRISM_MPI_MODULE", path("nowhere.so").c_str(), 1);
  const test::ProcessRun run =
      test::runPrismMpi(2, "render " + kScene + " -W 8 -H 8 -q -o " + path("x.png"));
  ::unsetenv("PRISM_MPI_MODULE");
  EXPECT_NE(run.exitCode, 0) << run.output;
  EXPECT_NE(run.exitCode, 124) << "timed out:\n" << run.output;
  EXPECT_NE(run.output.find("MPI's module prism_mpi.so was not found"), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("nowhere.so (absent)"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("PRISM_MPI_MODULE"), std::string::npos) << run.output;
  EXPECT_FALSE(std::filesystem::exists(path("x.png")));
}

#ifdef PRISM_HAVE_VIEWER
TEST_F(LazyLibraries, AMissingViewerModuleIsAClearErrorAndRenderNeedsNone) {
  const std::string env = "PRISM_VIEWER_MODULE=" + path("nowhere.so") + " ";
  const test::ProcessRun view = test::runCommand(env + "QT_QPA_PLATFORM=offscreen " +
                                                 std::string(PRISM_EXECUTABLE) + " view " + kScene);
  EXPECT_EQ(view.exitCode, 1) << view.output;
  EXPECT_NE(view.output.find("the viewer's module prism_viewer.so was not found"),
            std::string::npos)
      << view.output;
  EXPECT_NE(view.output.find("nowhere.so (absent)"), std::string::npos) << view.output;
  const test::ProcessRun render =
      test::runCommand(env + std::string(PRISM_EXECUTABLE) + " render " + kScene +
                       " -W 8 -H 8 -q -o " + path("x.png"));
  EXPECT_EQ(render.exitCode, 0) << render.output;
}
#endif

}  // namespace
}  // namespace prism
