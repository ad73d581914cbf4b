#include "master/frame/TilePlan.h"

#include <gtest/gtest.h>

namespace prism {
namespace {

TEST(TilePlan, TilesCoverEveryPixelExactlyOnce) {
  for (auto [w, h, tile] : {std::tuple{100, 37, 16}, std::tuple{64, 64, 64}, std::tuple{5, 3, 8}}) {
    std::vector<int> covered(static_cast<size_t>(w) * h, 0);
    for (const TileRect& r : planTiles(w, h, tile)) {
      EXPECT_LE(r.width, tile);
      EXPECT_LE(r.height, tile);
      for (int y = r.y; y < r.y + r.height; ++y)
        for (int x = r.x; x < r.x + r.width; ++x) ++covered[static_cast<size_t>(y) * w + x];
    }
    for (int c : covered) ASSERT_EQ(c, 1);
  }
}

TEST(TilePlan, AutomaticSizeGivesEachWorkerManyTilesWithinBounds) {
  const int size = automaticTileSize(1920, 1080, 2);
  EXPECT_EQ(size % 8, 0);
  EXPECT_GE(size, 8);
  EXPECT_LE(size, 64);
  EXPECT_GE(planTiles(640, 360, automaticTileSize(640, 360, 2)).size(), 32u);
  EXPECT_EQ(automaticTileSize(4, 4, 64), 8);
}

// The viewer's tiles: 1-spp frames get tiles of at least 16 k samples (128² on two threads
// at 640×360 and 1280×720, 15 and 60 of them), more samples per pixel smaller ones, many
// workers enough tiles to share (at least 4 each), and tiny images the 8-pixel minimum.
TEST(TilePlan, StreamedSizeKeepsTilesLargeAndSharedOut) {
  EXPECT_EQ(streamedTileSize(640, 360, 1, 2), 128);
  EXPECT_EQ(planTiles(640, 360, streamedTileSize(640, 360, 1, 2)).size(), 15u);
  EXPECT_EQ(planTiles(1280, 720, streamedTileSize(1280, 720, 1, 2)).size(), 60u);
  EXPECT_EQ(streamedTileSize(640, 360, 4, 2), 64);
  EXPECT_EQ(streamedTileSize(640, 360, 1, 32), 40);  // √(230400 / 128) = 42.4, down to 40
  EXPECT_GE(planTiles(640, 360, streamedTileSize(640, 360, 1, 32)).size(), 4u * 32u);
  EXPECT_EQ(streamedTileSize(4, 4, 1, 2), 8);
  EXPECT_EQ(streamedTileSize(7680, 4320, 1, 1), 128);
  for (int spp : {1, 2, 3, 16, 1000}) {
    const int size = streamedTileSize(1920, 1080, spp, 3);
    EXPECT_EQ(size % 8, 0) << spp;
    EXPECT_GE(size, 8) << spp;
    EXPECT_LE(size, 128) << spp;
  }
}

}  // namespace
}  // namespace prism
