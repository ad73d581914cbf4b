#include "master/analysis/TileCostMap.h"

#include <gtest/gtest.h>

#include <numeric>

#include "master/frame/TilePlan.h"

namespace prism {
namespace {

double sum(const std::vector<double>& v) {
  return std::accumulate(v.begin(), v.end(), 0.0);
}

TEST(TileCostMap, UniformCostScalesWithPixels) {
  // 64x32 in 16-pixel tiles, 1 µs per pixel everywhere.
  const std::vector<TileRect> tiles = planTiles(64, 32, 16);
  std::vector<double> seconds(tiles.size(), 256e-6);
  const TileCostMap map(64, 32, tiles, seconds);
  EXPECT_NEAR(map.totalSeconds(), 2048e-6, 1e-15);
  // Four times the pixels cost four times as much; every tile its pixel count in µs, edge
  // tiles (40 = 32 + 8) included.
  const std::vector<TileRect> bigger = planTiles(128, 64, 40);
  const std::vector<double> costs = map.tileCosts(128, 64, 40);
  ASSERT_EQ(costs.size(), bigger.size());
  for (size_t i = 0; i < costs.size(); ++i) {
    EXPECT_NEAR(costs[i], bigger[i].pixelCount() * 1e-6, 1e-12) << i;
  }
  EXPECT_NEAR(sum(costs), 4 * map.totalSeconds(), 1e-12);
}

TEST(TileCostMap, AnExpensiveRegionStaysWhereItWas) {
  // 32x32 in four 16-pixel tiles; the bottom-right tile costs 1 s, the others nothing.
  const std::vector<TileRect> tiles = planTiles(32, 32, 16);
  const TileCostMap map(32, 32, tiles, {0.0, 0.0, 0.0, 1.0});
  // At 64x64 in 16-pixel tiles (4x4), the cost lies in the bottom-right 2x2 tiles, 4 s in all.
  const std::vector<double> costs = map.tileCosts(64, 64, 16);
  ASSERT_EQ(costs.size(), 16u);
  for (int row = 0; row < 4; ++row) {
    for (int column = 0; column < 4; ++column) {
      const double expected = row >= 2 && column >= 2 ? 1.0 : 0.0;
      EXPECT_NEAR(costs[row * 4 + column], expected, 1e-12) << row << "," << column;
    }
  }
  // A tile straddling the border takes the share it covers: 24-pixel tiles at 32x32.
  const std::vector<double> straddling = map.tileCosts(32, 32, 24);
  EXPECT_NEAR(straddling[0], 8.0 * 8.0 / 256.0, 1e-12);  // 8x8 of the expensive tile
  EXPECT_NEAR(sum(straddling), 1.0, 1e-12);
}

TEST(TileCostMap, RejectsWhatIsNotAPlan) {
  const std::vector<TileRect> tiles = planTiles(32, 32, 16);
  EXPECT_THROW(TileCostMap(32, 32, tiles, {1.0}), std::invalid_argument);
  EXPECT_THROW(TileCostMap(48, 32, tiles, {1, 1, 1, 1}), std::invalid_argument);
}

}  // namespace
}  // namespace prism
