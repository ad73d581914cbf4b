// `prism view --serve` and `prism connect` end to end: the real executables, the job under
// mpiexec with 2 ranks or alone, the window offscreen.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <regex>
#include <thread>

#include "image/ImageIo.h"
#include "master/PrismProcess.h"  // tests/master/

namespace prism {
namespace {

using test::runPrism;

class RemoteViewer : public test::ScratchFolderTest {
 protected:
  void SetUp() override {
    test::ScratchFolderTest::SetUp();
    ::setenv("QT_QPA_PLATFORM", "offscreen", 1);
  }
  // Waits for the job to write its connection file.
  bool waitForFile(const std::string& file) {
    for (int i = 0; i < 600 && !std::filesystem::exists(file); ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return std::filesystem::exists(file);
  }
};

const std::string kScene = PRISM_SOURCE_DIR "/scenes/default.yaml";
const std::string kSize = " --width 96 --height 54 --spp 1";

TEST_F(RemoteViewer, TwoRanksServeAndTheDeskSavesWhatRenderMakesOfTheViewItMovedTo) {
  const std::string file = path("job.connection");
  test::ProcessRun job;
  std::thread server([&] {
    job = test::runPrismMpi(2, "view " + kScene + kSize + " --serve 0 --connection-file " + file +
                                   " --exit-with-client");
  });
  ASSERT_TRUE(waitForFile(file)) << "no connection file";
  const auto desk =
      runPrism("connect " + file + " --keys wwd --exit-after-passes 1 --save " + path("desk.exr"));
  server.join();
  ASSERT_EQ(desk.exitCode, 0) << desk.output;
  ASSERT_EQ(job.exitCode, 0) << job.output;
  EXPECT_NE(job.output.find("serving    127.0.0.1:"), std::string::npos) << job.output;
  EXPECT_NE(job.output.find("served     until the viewer left (--exit-with-client)"),
            std::string::npos)
      << job.output;
  EXPECT_FALSE(std::filesystem::exists(file)) << "the job leaves no connection file behind";
  // The desk printed the render options of the view it saved.
  std::smatch view;
  ASSERT_TRUE(std::regex_search(desk.output, view,
                                std::regex("view       (--camera-position \\S+ --look-at \\S+)")))
      << desk.output;
  const auto render =
      runPrism("render " + kScene + kSize + " " + view[1].str() + " -q -o " + path("render.exr"));
  ASSERT_EQ(render.exitCode, 0) << render.output;
  const ImageRgb a = readImage(path("desk.exr"));
  const ImageRgb b = readImage(path("render.exr"));
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  size_t different = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) different += a.pixels[i] != b.pixels[i];
  EXPECT_EQ(different, 0u);
  // The view moved: it is not the scene's own.
  const auto home = runPrism("render " + kScene + kSize + " -q -o " + path("home.exr"));
  EXPECT_NE(readImage(path("home.exr")).pixels, b.pixels);
}

TEST_F(RemoteViewer, CtrlCEndsTheJobAndTheWindowSaysSo) {
  const std::string file = path("job.connection");
  const std::string pidFile = path("job.pid");
  test::ProcessRun job;
  std::thread server([&] {
    job = test::runCommand("sh -c 'echo $$ > " + pidFile + "; exec " + PRISM_EXECUTABLE + " view " +
                           kScene + kSize + " --serve 0 --connection-file " + file + "'");
  });
  ASSERT_TRUE(waitForFile(file));
  test::ProcessRun desk;
  std::thread viewer([&] {
    desk = runPrism("connect " + file + " --screenshot-after 60 --screenshot " + path("x.png"));
  });
  std::this_thread::sleep_for(std::chrono::seconds(2));  // connected, frames arriving
  std::string pid;
  std::ifstream(pidFile) >> pid;
  ASSERT_FALSE(pid.empty());
  test::runCommand("kill -INT " + pid);
  viewer.join();
  server.join();
  EXPECT_EQ(job.exitCode, 130) << job.output;
  EXPECT_EQ(desk.exitCode, 1) << desk.output;
  EXPECT_NE(desk.output.find("prism: error: the job ended: the job was interrupted (SIGINT)"),
            std::string::npos)
      << desk.output;
}

TEST_F(RemoteViewer, MistakesAreClearErrors) {
  const auto wide = runPrism("view " + kScene + " --serve 0.0.0.0:0");
  EXPECT_EQ(wide.exitCode, 1);
  EXPECT_NE(wide.output.find("add --allow-network to mean it"), std::string::npos) << wide.output;
  const auto windowOption = runPrism("view " + kScene + " --serve 0 --save " + path("x.png"));
  EXPECT_EQ(windowOption.exitCode, 1);
  EXPECT_NE(windowOption.output.find("go to `prism connect`"), std::string::npos)
      << windowOption.output;
  const auto badAddress = runPrism("view " + kScene + " --serve host:port");
  EXPECT_EQ(badAddress.exitCode, 1);
  EXPECT_NE(badAddress.output.find("has no port number"), std::string::npos) << badAddress.output;
  const auto noToken = test::runCommand("env -u PRISM_TOKEN " + std::string(PRISM_EXECUTABLE) +
                                        " connect 127.0.0.1:9");
  EXPECT_EQ(noToken.exitCode, 1);
  EXPECT_NE(noToken.output.find("no token: pass --token-file FILE or set PRISM_TOKEN"),
            std::string::npos)
      << noToken.output;
  const auto nobody = test::runCommand("PRISM_TOKEN=x " + std::string(PRISM_EXECUTABLE) +
                                       " connect 127.0.0.1:9 --timeout 2");
  EXPECT_EQ(nobody.exitCode, 1);
  EXPECT_NE(nobody.output.find("cannot connect to 127.0.0.1:9"), std::string::npos)
      << nobody.output;
  const auto notAFile = runPrism("connect " + path("nothing-here"));
  EXPECT_EQ(notAFile.exitCode, 1);
  EXPECT_NE(notAFile.output.find("is neither a connection file nor HOST:PORT"), std::string::npos)
      << notAFile.output;
}

}  // namespace
}  // namespace prism
