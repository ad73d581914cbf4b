// End-to-end tests of `prism render`: the real executable, real files, exit codes and messages.
#include "master/RenderCommand.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "PrismProcess.h"
#include "image/ImageIo.h"
#include "parse/SceneLoader.h"
#include "scene/Camera.h"

namespace prism {
namespace {

namespace fs = std::filesystem;

using test::ProcessRun;
using test::runPrism;

class RenderCommandTest : public test::ScratchFolderTest {};

const std::string kSceneDir = std::string(PRISM_SOURCE_DIR) + "/scenes/";

TEST_F(RenderCommandTest, ClosedFormSceneGivesTheExactRadianceInTheExr) {
  const std::string scene = kSceneDir + "lambert-plane.yaml";
  const ProcessRun run = runPrism("render " + scene + " -o " + path("plane.exr") + " --threads 2");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("Mrays/s"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("written"), std::string::npos) << run.output;

  const ImageRgb image = readImage(path("plane.exr"));
  const SceneDescription d = loadScene(scene);
  ASSERT_EQ(image.width, d.render.width);
  const Camera camera(d.camera, d.render.width, d.render.height);
  const PointLightDesc& light = d.lights.at(0);
  const Color albedo = d.materials.at(0).diffuse;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const Ray ray = camera.generateRay(x + 0.5f, y + 0.5f);
      const Vec3 p = ray.at(-ray.origin.y / ray.direction.y);
      const Vec3 toLight = light.position - p;
      const float distance = glm::length(toLight);
      const Color expected =
          albedo / kPi * light.intensity * (toLight.y / distance) / (distance * distance);
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(image.at(x, y)[c], expected[c], 1e-5f * expected[c]);
    }
  }
}

TEST_F(RenderCommandTest, OverridesAndNffInput) {
  const ProcessRun run =
      runPrism("render " + std::string(PRISM_TEST_DATA_DIR) + "/nff/balls-s2.nff -o " +
               path("balls.png") + " -W 48 -H 32 --spp 2 --max-depth 2 -t 1");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("48x32, 2 spp, max depth 2"), std::string::npos) << run.output;
  const ImageRgb image = readImage(path("balls.png"));
  EXPECT_EQ(image.width, 48);
  EXPECT_EQ(image.height, 32);
}

TEST_F(RenderCommandTest, BadSceneGivesLocatedErrorNonZeroExitAndNoImage) {
  const std::string scene = path("bad.yaml");
  FILE* f = std::fopen(scene.c_str(), "w");
  std::fputs("objects:\n  - sphere: {center: [0, 0, 0], radius: -1}\n", f);
  std::fclose(f);
  const ProcessRun run = runPrism("render " + scene + " -o " + path("out.png"));
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_NE(run.output.find("bad.yaml:2:"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("radius"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(path("out.png")));
}

TEST_F(RenderCommandTest, MissingSceneFileIsNamed) {
  const ProcessRun run = runPrism("render " + path("nope.yaml") + " -o " + path("out.png"));
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_NE(run.output.find("nope.yaml"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(path("out.png")));
}

TEST_F(RenderCommandTest, UnsupportedOutputFormatIsRefusedBeforeRendering) {
  const ProcessRun run =
      runPrism("render " + kSceneDir + "lambert-plane.yaml -o " + path("out.xyz"));
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_NE(run.output.find("xyz"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("Mrays/s"), std::string::npos) << run.output;
}

TEST_F(RenderCommandTest, AbsurdImageSizeIsRefusedWithTheMemoryItNeeds) {
  const ProcessRun run = runPrism("render " + kSceneDir + "lambert-plane.yaml -o " + path("o.png") +
                                  " --width 1000000 --height 1000000");
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_NE(run.output.find("TiB"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(path("o.png")));
}

TEST_F(RenderCommandTest, HelpDescribesTheOptions) {
  const ProcessRun run = runPrism("render --help");
  EXPECT_EQ(run.exitCode, 0);
  for (const char* option : {"--output", "--threads", "--width", "--height", "--spp", "--max-depth",
                             "--tile-size", "--triangle-test", "--quiet"}) {
    EXPECT_NE(run.output.find(option), std::string::npos) << option;
  }
}

TEST_F(RenderCommandTest, InvalidOptionValueIsAUsageError) {
  const ProcessRun run = runPrism("render " + kSceneDir + "lambert-plane.yaml --spp 0");
  EXPECT_NE(run.exitCode, 0);
  EXPECT_NE(run.output.find("spp"), std::string::npos) << run.output;
}

TEST(RenderCommand, DefaultOutputIsTheSceneNameAsPng) {
  EXPECT_EQ(defaultOutputPath("scenes/default.yaml"), "default.png");
  EXPECT_EQ(defaultOutputPath("/x/y/teapot.nff"), "teapot.png");
}

}  // namespace
}  // namespace prism
