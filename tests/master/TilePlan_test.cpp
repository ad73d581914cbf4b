#include "master/TilePlan.h"

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

}  // namespace
}  // namespace prism
