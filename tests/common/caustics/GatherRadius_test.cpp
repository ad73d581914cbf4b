#include "caustics/GatherRadius.h"
#include "caustics/PhotonGather.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/common/caustics/BallOverFloorScene.h"

namespace prism {
namespace {

TEST(GatherRadius, Automatic) {
  SceneDescription d = test::ballOverFloorScene(1.0f);
  d.spheres.push_back({{5, 1, 0}, 2.5f, 0, {}});
  EXPECT_FLOAT_EQ(automaticMaxRadius(Scene(d)), 0.25f);  // a tenth of the largest caster
  // Only a casting plane: a hundredth of the bounded objects' extent (the diffuse sphere's box,
  // 2 × 2 × 2: diagonal 2√3).
  SceneDescription planes;
  MaterialDesc mirror;
  mirror.reflectance = Color(1.0f);
  planes.materials = {mirror, MaterialDesc{}};
  planes.planes.push_back({{0, 0, 0}, {0, 1, 0}, 0, {}});
  planes.spheres.push_back({{0, 3, 0}, 1.0f, 1, {}});
  EXPECT_NEAR(automaticMaxRadius(Scene(planes)), 0.02f * std::sqrt(3.0f), 1e-6f);
}

// Per-photon radii: the distance to the k-th nearest photon, itself counted first. Photons on a
// line with unit spacing: the 3rd nearest of an interior photon is 1 away, of an end photon 2.
TEST(GatherRadius, PhotonRadiiAreTheKthNeighbourDistanceCapped) {
  std::vector<Photon> line(300);
  for (size_t i = 0; i < line.size(); ++i) line[i].position = {static_cast<float>(i), 0, 0};
  const PhotonMap map(std::move(line));
  const std::vector<float> radii = photonRadii(map, 3, 10.0f, 2);
  ASSERT_EQ(radii.size(), 300u);
  EXPECT_FLOAT_EQ(radii[0], 2.0f);
  EXPECT_FLOAT_EQ(radii[150], 1.0f);
  EXPECT_FLOAT_EQ(radii[299], 2.0f);
  EXPECT_FLOAT_EQ(photonRadii(map, 3, 1.5f, 2)[0], 1.5f);  // capped
}

// The progressive schedule: r²(i) = r²(i−1)·(i − 1 + α)/i, applied to the one fixed radius when
// the scene sets it, else to the per-photon radii through their common scale (1 at pass 1).
TEST(GatherRadius, ProgressiveScheduleShrinksByTheAlphaRule) {
  CausticSettings c;
  c.gather = 50;
  c.alpha = 0.5f;
  PhotonGatherSettings g = progressiveGather(c, 0.2f, 1, {});
  EXPECT_FALSE(g.fixedRadius);
  EXPECT_EQ(g.k, 50);
  EXPECT_FLOAT_EQ(g.radius, 0.2f);
  EXPECT_FLOAT_EQ(g.radiusScale, 1.0f);
  g = progressiveGather(c, 0.2f, 2, g);
  EXPECT_FLOAT_EQ(g.radiusScale * g.radiusScale, 1.5f / 2.0f);
  g = progressiveGather(c, 0.2f, 3, g);
  EXPECT_FLOAT_EQ(g.radiusScale * g.radiusScale, (1.5f / 2.0f) * (2.5f / 3.0f));
  EXPECT_FLOAT_EQ(g.radius, 0.2f);  // the cap is scaled with the radii, not here

  c.radius = 0.1f;
  g = progressiveGather(c, 0.2f, 1, {});
  EXPECT_TRUE(g.fixedRadius);
  EXPECT_FLOAT_EQ(g.radius, 0.1f);
  g = progressiveGather(c, 0.2f, 2, g);
  EXPECT_FLOAT_EQ(g.radius * g.radius, 0.01f * 0.75f);
}

}  // namespace
}  // namespace prism
