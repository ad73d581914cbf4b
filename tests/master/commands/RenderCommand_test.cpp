// End-to-end tests of `prism render`: the real executable, real files, exit codes and messages.
#include "master/commands/RenderCommand.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "image/ImageIo.h"
#include "master/PrismProcess.h"
#include "parse/SceneLoader.h"
#include "scene/Camera.h"

namespace prism {
namespace {

namespace fs = std::filesystem;

using test::ProcessRun;
using test::runPrism;
using test::runPrismMpi;

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

// A light too bright for floats makes samples infinite near it. None reaches the image: each
// such sample is black, and the summary counts them, the same for 1 and 2 ranks; an ordinary
// scene says every sample was finite.
TEST_F(RenderCommandTest, NonFiniteSamplesAreBlackAndCounted) {
  const std::string scene = std::string(PRISM_TEST_DATA_DIR) + "/scenes/non-finite.yaml";
  const auto count = [](const std::string& output) -> long {
    const auto at = output.find("numbers   ");
    if (at == std::string::npos) return -1;
    return std::strtol(output.c_str() + at + 10, nullptr, 10);
  };
  const ProcessRun run = runPrism("render " + scene + " -o " + path("one.exr"));
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const long nonFinite = count(run.output);
  EXPECT_GT(nonFinite, 0) << run.output;
  const ImageRgb image = readImage(path("one.exr"));
  long black = 0;
  for (const Color& c : image.pixels) {
    ASSERT_TRUE(isFinite(c));
    black += c == Color(0.0f);
  }
  EXPECT_EQ(black, nonFinite);  // one sample per pixel, and the floor is lit everywhere else
  const ProcessRun two = runPrismMpi(2, "render " + scene + " -o " + path("two.exr"));
  ASSERT_EQ(two.exitCode, 0) << two.output;
  EXPECT_EQ(count(two.output), nonFinite) << two.output;

  const ProcessRun plain =
      runPrism("render " + kSceneDir + "lambert-plane.yaml -o " + path("plain.exr"));
  EXPECT_NE(plain.output.find("numbers   every sample finite"), std::string::npos) << plain.output;
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

// ---- caustics -------------------------------------------------------------------------------

const std::string kCausticScene = std::string(PRISM_TEST_DATA_DIR) + "/scenes/caustic-small.yaml";

TEST_F(RenderCommandTest, CausticRunSummarisesThePhotonPassesAndWritesAPhotonImage) {
  const ProcessRun run = runPrism("render " + kCausticScene + " -o " + path("c.exr") +
                                  " --photon-image " + path("photons.png") + " --threads 2");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("caustics  photon map: 20.0 k photons x 1 pass"), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("28 B per photon"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("each photon over its 40-NN radius within"), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("kd-tree"), std::string::npos) << run.output;
  ASSERT_TRUE(fs::exists(path("photons.png")));
  const ImageRgb photons = readImage(path("photons.png"));
  EXPECT_EQ(photons.width, 40);
  EXPECT_EQ(photons.height, 30);
  size_t lit = 0;
  for (const Color& c : photons.pixels) lit += maxComponent(c) > 0.0f;
  EXPECT_GT(lit, 10u) << "the photon image shows no photons";

  const ProcessRun progressive =
      runPrism("render " + kCausticScene + " -o " + path("p.exr") + " --progressive --passes 2");
  ASSERT_EQ(progressive.exitCode, 0) << progressive.output;
  EXPECT_NE(progressive.output.find("photon map (progressive): 20.0 k photons x 2 passes"),
            std::string::npos)
      << progressive.output;
  EXPECT_NE(progressive.output.find(", shrunk to "), std::string::npos) << progressive.output;
  EXPECT_EQ(progressive.output.find("budget "), std::string::npos) << progressive.output;
}

// A time budget asks for progressive passes by itself (it was ignored without --progressive),
// runs them until it ends unless --passes gives a count, and says what it bounded; beside
// caustic mapping, which has no passes, it says it was not used.
TEST_F(RenderCommandTest, ATimeBudgetRunsProgressivePassesAndSaysWhatItBounded) {
  // Far above what this run takes: all passes fit.
  const ProcessRun budgeted = runPrism("render " + kCausticScene + " -o " + path("b.exr") +
                                       " --passes 2 --time-budget 1000");
  ASSERT_EQ(budgeted.exitCode, 0) << budgeted.output;
  EXPECT_NE(budgeted.output.find("budget    1000.00 s for the whole run, start to written image: "
                                 "all 2 passes fitted"),
            std::string::npos)
      << budgeted.output;
  EXPECT_NE(budgeted.output.find("photon map (progressive): 20.0 k photons x 2 passes"),
            std::string::npos)
      << budgeted.output;

  // Without --passes a budget runs passes until it ends (here at once: set-up alone takes more
  // than a millisecond, and the first pass always runs).
  const ProcessRun open =
      runPrism("render " + kCausticScene + " -o " + path("o.exr") + " --time-budget 0.001");
  ASSERT_EQ(open.exitCode, 0) << open.output;
  EXPECT_NE(open.output.find("budget    0.00 s for the whole run, start to written image: 1 pass; "
                             "at "),
            std::string::npos)
      << open.output;

  // Caustic mapping has no passes for a budget to bound: said, not silently ignored.
  const ProcessRun mapped = runPrism("render " + kCausticScene + " -o " + path("m.exr") +
                                     " --caustics caustic-map --time-budget 5");
  ASSERT_EQ(mapped.exitCode, 0) << mapped.output;
  EXPECT_NE(mapped.output.find("warning: a time budget bounds progressive photon passes, and "
                               "caustic mapping renders one frame"),
            std::string::npos)
      << mapped.output;
}

// Caustics on a scene with no caster: a warning, no photon cost, and the very same pixels as
// a render without caustics.
TEST_F(RenderCommandTest, CausticsWithoutACasterWarnAndRenderTheSameImage) {
  const std::string scene = kSceneDir + "lambert-plane.yaml";
  const ProcessRun plain = runPrism("render " + scene + " -q -o " + path("plain.exr"));
  ASSERT_EQ(plain.exitCode, 0) << plain.output;
  const ProcessRun caustic =
      runPrism("render " + scene + " -o " + path("caustic.exr") +
               " --caustics photon-map --photon-image " + path("photons.png"));
  ASSERT_EQ(caustic.exitCode, 0) << caustic.output;
  EXPECT_NE(caustic.output.find("warning: caustics asked for, but no light reaches a caustic "
                                "caster"),
            std::string::npos)
      << caustic.output;
  EXPECT_NE(caustic.output.find("no light reaches a caster: no photons traced"), std::string::npos)
      << caustic.output;
  const ImageRgb a = readImage(path("plain.exr")), b = readImage(path("caustic.exr"));
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  EXPECT_EQ(std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Color)), 0);
}

TEST_F(RenderCommandTest, CausticOptionsAreListedAndChecked) {
  const ProcessRun help = runPrism("render --help");
  for (const char* option : {"--caustics", "--photons", "--gather", "--gather-radius",
                             "--progressive", "--passes", "--time-budget", "--photon-image"}) {
    EXPECT_NE(help.output.find(option), std::string::npos) << option;
  }
  for (const char* bad : {"--photons 0", "--gather 0", "--gather-radius -1", "--passes 0",
                          "--caustics sideways", "--time-budget 0"}) {
    const ProcessRun run = runPrism("render " + kCausticScene + " -o " + path("x.exr") + " " + bad);
    EXPECT_NE(run.exitCode, 0) << bad << "\n" << run.output;
    EXPECT_FALSE(fs::exists(path("x.exr"))) << bad;
  }
}

// --- Limits (docs/reliability.md, "Limits"): refused before anything is allocated, with the
// bytes and the limit, one line, exit 1, no file.

TEST_F(RenderCommandTest, MemoryLimitRefusesTheFrameWithItsBytesAndWritesNothing) {
  const ProcessRun run = runPrism("render " + kSceneDir + "lambert-plane.yaml -o " + path("o.png") +
                                  " -W 1000 -H 1000 --memory-limit 1M");
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_EQ(run.output,
            "prism: error: a 1000x1000 image's frame buffer needs 22.9 MiB (24000000 bytes); the "
            "memory limit is 1.0 MiB (1048576 bytes, --memory-limit): reduce --width/--height\n");
  EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(RenderCommandTest, MemoryLimitRefusesAMeshBeforeReadingItWithTheSceneLine) {
  const ProcessRun run =
      runPrism("render " + kSceneDir + "default.yaml -o " + path("o.png") + " --memory-limit 2M");
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_NE(run.output.find("default.yaml:78:13: mesh file '"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("trefoil.obj' (9600 triangles, 4800 vertices) read and built needs "
                            "3.5 MiB (3625071 bytes); the memory limit is 2.0 MiB (2097152 bytes, "
                            "--memory-limit)"),
            std::string::npos)
      << run.output;
  EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(RenderCommandTest, TileCountAndSampleBoundsAreRefused) {
  ProcessRun run = runPrism("render " + kSceneDir + "lambert-plane.yaml -o " + path("o.png") +
                            " -W 100000 -H 100000 --tile-size 1 --memory-limit 1T");
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_EQ(run.output,
            "prism: error: a 100000x100000 image in 1-pixel tiles makes 10000000000 tiles; at most "
            "16777216 are allowed (raise --tile-size)\n");
  // --spp has the same bound as a range; a scene file can ask for more.
  std::ifstream in(kSceneDir + "lambert-plane.yaml");
  std::string scene((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  scene.replace(scene.find("samples: 1"), 10, "samples: 100000");
  std::ofstream(path("many-samples.yaml")) << scene;
  run = runPrism("render " + path("many-samples.yaml") + " -o " + path("o.png"));
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_NE(run.output.find("many-samples.yaml:"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find(": 'samples' must be at most 65536, found 100000\n"), std::string::npos)
      << run.output;
  run =
      runPrism("render " + kSceneDir + "lambert-plane.yaml -o " + path("o.png") + " --spp 100000");
  EXPECT_NE(run.exitCode, 0);
  EXPECT_NE(run.output.find("--spp: Value 100000 not in range 1 to 65536"), std::string::npos)
      << run.output;
  EXPECT_FALSE(fs::exists(path("o.png")));
}

// One name table and one set of limits (scene/SettingNames.h, SettingLimits.h): a value copied
// from a scene file works as an option, in either spelling, and the command line refuses what
// the scene parser and the codec refuse.
TEST_F(RenderCommandTest, OptionsTakeTheSceneFilesNamesAndLimits) {
  const std::string base = "render " + std::string(PRISM_TEST_DATA_DIR) +
                           "/scenes/caustic-small.yaml -W 16 -H 12 --photons 2000 -t 1 -q "
                           "--overwrite -o " +
                           path("c.exr");
  for (const char* method : {"photon_map", "photon-map", "PHOTON_MAP", "caustic_map", "map"}) {
    const ProcessRun run = runPrism(base + " --caustics " + method);
    EXPECT_EQ(run.exitCode, 0) << method << ": " << run.output;
  }
  for (const char* test : {"plane_inside", "plane-inside", "moller_trumbore"}) {
    const ProcessRun run = runPrism(base + " --triangle-test " + test);
    EXPECT_EQ(run.exitCode, 0) << test << ": " << run.output;
  }
  EXPECT_EQ(runPrism(base + " --max-depth 256").exitCode, 0);  // the scene file's bound
  ProcessRun run = runPrism(base + " --max-depth 257");
  EXPECT_NE(run.exitCode, 0);
  EXPECT_NE(run.output.find("--max-depth: Value 257 not in range 0 to 256"), std::string::npos)
      << run.output;
  run = runPrism(base + " --caustics photons");
  EXPECT_NE(run.exitCode, 0);
  EXPECT_NE(run.output.find("--caustics: unknown value 'photons' (expected none, photon_map or "
                            "caustic_map)"),
            std::string::npos)
      << run.output;
  const ProcessRun help = runPrism("render --help");
  EXPECT_NE(help.output.find("none|photon_map|caustic_map"), std::string::npos) << help.output;
}

TEST_F(RenderCommandTest, MemoryLimitIsCheckedUnderMpiBeforeTheSlavesGetAScene) {
  const ProcessRun run = runPrismMpi(2, "render " + kSceneDir + "lambert-plane.yaml -o " +
                                            path("o.png") + " -W 1000 -H 1000 --memory-limit 1M");
  EXPECT_NE(run.exitCode, 0);
  EXPECT_NE(run.output.find("prism: error: a 1000x1000 image's frame buffer needs 22.9 MiB"),
            std::string::npos)
      << run.output;
  EXPECT_TRUE(fs::is_empty(dir_));
}

// A light among its casters needs six caustic-map views, which only the built scene tells:
// the check before the broadcast counts one (it passes), the one after the build six (refused),
// in one process and with a slave, before any map is built.
TEST_F(RenderCommandTest, CausticMapsOfALightAmongItsCastersAreCheckedOnceTheSceneIsBuilt) {
  std::ofstream(path("lamp.yaml"))
      << "camera: {position: [0, 3, 8], look_at: [0, 1, 0], fov: 40}\n"
         "render: {width: 64, height: 48, samples: 1}\n"
         "caustics: {method: caustic_map, map_resolution: 2048}\n"
         "materials:\n"
         "  - {name: glass, diffuse: 0, transmittance: 1, ior: 1.5}\n"
         "  - {name: floor, diffuse: 0.8}\n"
         "lights: [{position: [0, 2, 0], intensity: 50}]\n"
         "objects:\n"
         "  - sphere: {center: [0, 2, 0], radius: 0.5, material: glass}\n"
         "  - plane: {point: [0, 0, 0], normal: [0, 1, 0], material: floor}\n";
  const std::string refusal =
      "prism: error: caustic maps of 1 light at 2048 texels a side (6 views) needs 3.1 GiB "
      "(3321888768 bytes); the memory limit is 2.0 GiB (2147483648 bytes, --memory-limit): "
      "reduce --map-resolution\n";
  const std::string args =
      "render " + path("lamp.yaml") + " -o " + path("o.png") + " --memory-limit 2G";
  ProcessRun run = runPrism(args);
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_NE(run.output.find(refusal), std::string::npos) << run.output;
  run = runPrismMpi(2, args);
  EXPECT_NE(run.exitCode, 0);
  EXPECT_NE(run.output.find(refusal), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(path("o.png")));
}

TEST_F(RenderCommandTest, MemoryLimitMustBeASize) {
  const ProcessRun run = runPrism("render " + kSceneDir + "lambert-plane.yaml -o " + path("o.png") +
                                  " --memory-limit 12Q");
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_EQ(run.output,
            "prism: error: --memory-limit: '12Q' is not a size (examples: 512M, 8G, 1.5T, "
            "1000000)\n");
}

// --- Overwriting (docs/reliability.md, "Nothing lost").

TEST_F(RenderCommandTest, AFinishedFrameIsNotOverwrittenWithoutOverwrite) {
  const std::string render = "render " + kSceneDir + "lambert-plane.yaml -W 16 -H 8 -q -o ";
  ASSERT_EQ(runPrism(render + path("o.exr")).exitCode, 0);
  const auto written = fs::last_write_time(path("o.exr"));
  const ProcessRun again = runPrism(render + path("o.exr") + " --spp 2");
  EXPECT_EQ(again.exitCode, 1);
  EXPECT_EQ(again.output, "prism: error: '" + path("o.exr") +
                              "' already exists; pass --overwrite to replace it (nothing "
                              "rendered)\n");
  EXPECT_EQ(fs::last_write_time(path("o.exr")), written);
  const ProcessRun replaced = runPrism(render + path("o.exr") + " --spp 2 --overwrite");
  EXPECT_EQ(replaced.exitCode, 0) << replaced.output;
}

TEST_F(RenderCommandTest, APartialFrameAtTheOutputPathMayBeReplaced) {
  writeImage(ImageRgb(2, 2), path("o.png"), 1.0f, {{"PrismPartial", "1/4"}});
  const ProcessRun run =
      runPrism("render " + kSceneDir + "lambert-plane.yaml -W 16 -H 8 -q -o " + path("o.png"));
  EXPECT_EQ(run.exitCode, 0) << run.output;
  EXPECT_EQ(readImage(path("o.png")).width, 16);
}

#ifdef PRISM_HAVE_VIEWER
TEST_F(RenderCommandTest, ViewSaveDoesNotOverwriteAFinishedFrameEither) {
  writeImage(ImageRgb(2, 2), path("v.png"));
  const ProcessRun run =
      runPrism("view " + kSceneDir + "lambert-plane.yaml --save " + path("v.png"));
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_NE(run.output.find("already exists; pass --overwrite"), std::string::npos) << run.output;
}
#endif

TEST_F(RenderCommandTest, HelpListsTheReliabilityOptions) {
  const ProcessRun run = runPrism("render --help");
  for (const char* option : {"--memory-limit", "--overwrite", "--save-partial"}) {
    EXPECT_NE(run.output.find(option), std::string::npos) << option;
  }
  EXPECT_EQ(run.output.find("--status-file"), std::string::npos);  // for tests only
}

}  // namespace
}  // namespace prism
