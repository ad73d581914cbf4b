#include "master/commands/PartialFrame.h"

#include <gtest/gtest.h>

#include <fstream>

#include "image/ImageIo.h"
#include "master/PrismProcess.h"

namespace prism {
namespace {

TEST(PartialFrame, NameSaysPartialAndKeepsTheFormat) {
  EXPECT_EQ(partialOutputPath("frame.png"), "frame.partial.png");
  EXPECT_EQ(partialOutputPath("out/dir/frame.exr"), "out/dir/frame.partial.exr");
}

TEST(PartialFrame, OnlyUnfinishedTilesAreStriped) {
  ImageRgb image(8, 4);
  for (Color& c : image.pixels) c = Color(0.25f);
  const std::vector<TileRect> tiles = {{0, 0, 4, 4}, {4, 0, 4, 4}};
  markUnfinishedTiles(image, tiles, {true, false});
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 4; ++x) EXPECT_EQ(image.at(x, y), Color(0.25f));
    for (int x = 4; x < 8; ++x) {
      EXPECT_EQ(image.at(x, y), ((x + y) / 4) % 2 == 0 ? Color(1, 0, 1) : Color(0.0f));
    }
  }
}

class PartialFrameFiles : public test::ScratchFolderTest {};

TEST_F(PartialFrameFiles, MetadataSurvivesPngAndExr) {
  const ImageRgb image(4, 4);
  for (const char* name : {"p.png", "p.exr"}) {
    writeImage(image, path(name), 1.0f, partialFrameMetadata(57, 120));
    EXPECT_EQ(readImageText(path(name), kPartialFrameAttribute), "57/120") << name;
    EXPECT_EQ(readImageText(path(name), "ImageDescription"),
              "Prism partial render (interrupted): 57 of 120 tiles finished; unfinished tiles are "
              "striped magenta")
        << name;
    EXPECT_TRUE(isPartialFrame(path(name)));
  }
  writeImage(image, path("full.png"));
  EXPECT_FALSE(isPartialFrame(path("full.png")));
  EXPECT_FALSE(isPartialFrame(path("missing.png")));
}

TEST_F(PartialFrameFiles, AFinishedFrameIsReplacedOnlyWhenAskedAPartialOneAlways) {
  EXPECT_NO_THROW(checkMayWriteFrame(path("new.png"), false));
  writeImage(ImageRgb(2, 2), path("done.png"));
  try {
    checkMayWriteFrame(path("done.png"), false);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()),
              "'" + path("done.png") +
                  "' already exists; pass --overwrite to replace it (nothing rendered)");
  }
  EXPECT_NO_THROW(checkMayWriteFrame(path("done.png"), true));
  writeImage(ImageRgb(2, 2), path("half.png"), 1.0f, partialFrameMetadata(1, 2));
  EXPECT_NO_THROW(checkMayWriteFrame(path("half.png"), false));
  std::ofstream(path("notes.png")) << "not an image, but someone's file";
  EXPECT_THROW(checkMayWriteFrame(path("notes.png"), false), std::runtime_error);
}

}  // namespace
}  // namespace prism
