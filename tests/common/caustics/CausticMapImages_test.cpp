// The caustic map's debug images: one texel per pixel, rows top down, empty texels black,
// positions inside the unit cube, and the irradiance white at the 99.5th percentile of the lit
// texels so the focus does not leave the rest of the caustic black.
#include "caustics/CausticMapImages.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tests/common/caustics/BallOverFloorScene.h"

namespace prism {
namespace {

TEST(CausticMapImages, OnePixelPerTexelWithTheCausticWhiteAtThePercentile) {
  SceneDescription d = test::ballOverFloorScene(1.5f);
  d.caustics.mapResolution = 64;
  const Scene scene(d);
  const CausticMap map(scene, 0, scene.causticSettings(), 1);
  const std::vector<NamedImage> images = causticMapImages(map);
  ASSERT_EQ(images.size(), 4u);
  const char* names[] = {"receivers", "casters", "normals", "caustics"};
  for (size_t i = 0; i < images.size(); ++i) {
    EXPECT_EQ(images[i].name, names[i]);
    EXPECT_EQ(images[i].image.width, 64);
    EXPECT_EQ(images[i].image.height, 64);
  }
  size_t lit = 0, white = 0;
  for (int j = 0; j < 64; ++j) {
    for (int i = 0; i < 64; ++i) {
      const size_t texel = static_cast<size_t>(j) * 64 + i;
      const size_t pixel = static_cast<size_t>(63 - j) * 64 + i;  // row 0 is the grid's bottom
      const Color receiver = images[0].image.pixels[pixel];
      const Color caster = images[1].image.pixels[pixel];
      EXPECT_EQ(receiver == Color(0.0f), !map.receivers().at(0, i, j).valid);
      EXPECT_EQ(caster == Color(0.0f), !map.casters()[texel].valid);
      for (const Color& c : {receiver, caster}) {
        EXPECT_GE(std::min({c.x, c.y, c.z}), 0.0f);
        EXPECT_LE(std::max({c.x, c.y, c.z}), 1.0f + 1e-6f);
      }
      const float e = images[3].image.pixels[pixel].x;
      lit += e > 0.0f;
      white += e >= 1.0f;
    }
  }
  ASSERT_GT(lit, 1000u);
  // The texels at or above the percentile: 0.5 % of the lit ones, within one texel's rounding,
  // and give or take the texels tied with the one at the percentile (a symmetric caustic has
  // groups of texels equal to a few units in the last place).
  std::vector<float> sorted;
  for (size_t k = 0; k < map.texelCount(); ++k) {
    const float e = maxComponent(map.texelIrradiance(k));
    if (e > 0.0f) sorted.push_back(e);
  }
  std::sort(sorted.begin(), sorted.end());
  const float atPercentile = sorted[static_cast<size_t>(kCausticWhitePercentile * sorted.size())];
  const auto ties = std::count_if(sorted.begin(), sorted.end(), [&](float e) {
    return std::fabs(e - atPercentile) <= 1e-6f * atPercentile;
  });
  EXPECT_NEAR(static_cast<double>(white), (1.0 - kCausticWhitePercentile) * lit,
              1.5 + static_cast<double>(ties - 1));
}

}  // namespace
}  // namespace prism
