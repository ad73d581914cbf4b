#include "image/OiioModule.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "image/ImageIo.h"
#include "master/PrismProcess.h"

namespace prism {
namespace {

namespace fs = std::filesystem;

class OiioModuleTest : public test::ScratchFolderTest {};

// The shared objects this process has mapped whose file name contains `name`.
bool mapsLibrary(const std::string& name) {
  std::ifstream maps("/proc/self/maps");
  std::string line;
  while (std::getline(maps, line)) {
    if (line.find(name) != std::string::npos) return true;
  }
  return false;
}

ImageRgb testCard() {
  ImageRgb image(6, 4);
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 6; ++x) image.at(x, y) = Color(x / 5.0f, y / 3.0f, 0.25f * ((x + y) % 3));
  }
  return image;
}

// ctest runs each test in a process of its own, so this one starts with nothing loaded; run
// with the whole suite in one process, an earlier test may have loaded the module already.
TEST_F(OiioModuleTest, PngAndExrNeverLoadOpenImageIo) {
  if (oiioModuleLoaded()) GTEST_SKIP() << "an earlier test in this process loaded the module";
  ASSERT_FALSE(mapsLibrary("libOpenImageIO"));
  writeImage(testCard(), path("a.png"), 1.0f, {{"PrismPartial", "1/2"}});
  writeImage(testCard(), path("a.exr"));
  EXPECT_EQ(readImage(path("a.png")).width, 6);
  EXPECT_EQ(readImage(path("a.exr")).width, 6);
  EXPECT_EQ(readImageText(path("a.png"), "PrismPartial"), "1/2");
  EXPECT_TRUE(isWritableImagePath(path("b.exr")));
  EXPECT_FALSE(oiioModuleLoaded());
  EXPECT_FALSE(mapsLibrary("libOpenImageIO"));
  EXPECT_FALSE(mapsLibrary("prism_image_oiio"));
  EXPECT_TRUE(mapsLibrary("libpng16"));
  EXPECT_TRUE(mapsLibrary("libOpenEXRCore"));

  // The first other format loads it (so the check above can see a loaded module).
  writeImage(testCard(), path("a.tif"));
  EXPECT_TRUE(oiioModuleLoaded());
  EXPECT_TRUE(mapsLibrary("libOpenImageIO"));
}

// The same, seen from outside: the dynamic loader's own log of a render's process.
TEST_F(OiioModuleTest, ARenderToPngOrExrDoesNotLoadOpenImageIo) {
  const std::string scene = std::string(PRISM_SOURCE_DIR) + "/scenes/lambert-plane.yaml";
  for (const char* output : {"f.png", "f.exr"}) {
    const test::ProcessRun run =
        test::runCommand("LD_DEBUG=files " + std::string(PRISM_EXECUTABLE) + " render " + scene +
                         " -W 16 -H 8 -q -o " + path(output));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_NE(run.output.find("libpng16"), std::string::npos) << "the log shows libraries";
    EXPECT_EQ(run.output.find("libOpenImageIO"), std::string::npos) << output;
    EXPECT_EQ(run.output.find("prism_image_oiio"), std::string::npos) << output;
  }
  const test::ProcessRun tif =
      test::runCommand("LD_DEBUG=files " + std::string(PRISM_EXECUTABLE) + " render " + scene +
                       " -W 16 -H 8 -q -o " + path("f.tif"));
  ASSERT_EQ(tif.exitCode, 0) << tif.output;
  EXPECT_NE(tif.output.find("libOpenImageIO"), std::string::npos);
  EXPECT_EQ(readImage(path("f.tif")).width, 16);
}

TEST_F(OiioModuleTest, TiffHoldsTheSameBytesAsPng) {
  const ImageRgb card = testCard();
  writeImage(card, path("c.png"), 0.8f);
  writeImage(card, path("c.tif"), 0.8f);  // through OpenImageIO, the same display encoding
  const ImageRgb png = readImage(path("c.png")), tif = readImage(path("c.tif"));
  ASSERT_EQ(tif.width, 6);
  ASSERT_EQ(tif.height, 4);
  for (size_t i = 0; i < png.pixels.size(); ++i) EXPECT_EQ(tif.pixels[i], png.pixels[i]) << i;
}

TEST_F(OiioModuleTest, HdrKeepsRadianceToRgbePrecision) {
  const ImageRgb card = testCard();
  writeImage(card, path("c.hdr"), 123.0f);  // a float format: exposure must not touch it
  const ImageRgb back = readImage(path("c.hdr"));
  ASSERT_EQ(back.width, 6);
  for (size_t i = 0; i < card.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      // RGBE: an 8-bit mantissa shared by the three channels, relative to the largest.
      const float largest = std::max({card.pixels[i].x, card.pixels[i].y, card.pixels[i].z});
      EXPECT_NEAR(back.pixels[i][c], card.pixels[i][c], largest / 128.0f) << i << " " << c;
    }
  }
}

TEST_F(OiioModuleTest, MetadataOfOtherFormatsReadsThroughTheModule) {
  writeImage(testCard(), path("m.tif"), 1.0f, {{"ImageDescription", "a card"}});
  EXPECT_EQ(readImageText(path("m.tif"), "ImageDescription"), "a card");
  EXPECT_EQ(readImageText(path("missing.tif"), "ImageDescription"), "");
}

TEST_F(OiioModuleTest, CorruptOtherFormatsNameTheFile) {
  {
    std::ofstream out(path("bad.jpg"), std::ios::binary);
    out << "\xff\xd8\xff not a jpeg";
  }
  try {
    readImage(path("bad.jpg"));
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.jpg"), std::string::npos) << e.what();
  }
}

TEST_F(OiioModuleTest, AMissingModuleIsAClearErrorAndPngNeedsNone) {
  // Child processes, so that this one's loaded module (if any) does not answer.
  const std::string prism =
      "PRISM_OIIO_MODULE=" + path("nowhere.so") + " " + std::string(PRISM_EXECUTABLE) + " render " +
      std::string(PRISM_SOURCE_DIR) + "/scenes/lambert-plane.yaml -W 8 -H 8 -q -o ";
  const test::ProcessRun tif = test::runCommand(prism + path("x.tif"));
  EXPECT_EQ(tif.exitCode, 1) << tif.output;
  EXPECT_NE(tif.output.find("cannot write '.tif' images"), std::string::npos) << tif.output;
  EXPECT_NE(tif.output.find("nowhere.so (absent)"), std::string::npos) << tif.output;
  EXPECT_NE(tif.output.find("PRISM_OIIO_MODULE"), std::string::npos) << tif.output;
  EXPECT_FALSE(fs::exists(path("x.tif")));
  const test::ProcessRun png = test::runCommand(prism + path("x.png"));
  EXPECT_EQ(png.exitCode, 0) << png.output;
  EXPECT_TRUE(fs::exists(path("x.png")));
}

}  // namespace
}  // namespace prism
