#include "render/PixelSampler.h"

#include <gtest/gtest.h>

#include <set>

namespace prism {
namespace {

TEST(PixelSampler, GridHasExactlySppStrataAsSquareAsPossible) {
  const std::pair<int, std::pair<int, int>> cases[] = {
      {1, {1, 1}}, {4, {2, 2}}, {6, {3, 2}}, {8, {4, 2}}, {9, {3, 3}}, {7, {7, 1}}, {16, {4, 4}}};
  for (const auto& [spp, grid] : cases) {
    const PixelSampler s(spp);
    EXPECT_EQ(s.columns(), grid.first) << spp;
    EXPECT_EQ(s.rows(), grid.second) << spp;
  }
}

TEST(PixelSampler, OneSampleGoesThroughThePixelCentre) {
  Pcg32 rng(1, 1);
  EXPECT_EQ(PixelSampler(1).offset(0, rng), Vec2(0.5f));
}

TEST(PixelSampler, EverySampleFallsInItsOwnStratum) {
  for (int spp : {4, 6, 12, 25}) {
    const PixelSampler s(spp);
    Pcg32 rng(3, 4);
    std::set<std::pair<int, int>> strata;
    for (int i = 0; i < spp; ++i) {
      const Vec2 o = s.offset(i, rng);
      ASSERT_GE(o.x, 0.0f);
      ASSERT_LT(o.x, 1.0f);
      ASSERT_GE(o.y, 0.0f);
      ASSERT_LT(o.y, 1.0f);
      strata.insert({static_cast<int>(o.x * s.columns()), static_cast<int>(o.y * s.rows())});
    }
    EXPECT_EQ(strata.size(), static_cast<size_t>(spp));
  }
}

}  // namespace
}  // namespace prism
