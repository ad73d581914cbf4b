#include "caustics/GatherRadius.h"

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

  // The first progressive radius: the mean distance to the k-th neighbour. Photons on a line
  // with unit spacing: the 2nd nearest of each interior photon (itself first) is 1 away.
  std::vector<Photon> line(300);
  for (size_t i = 0; i < line.size(); ++i) line[i].position = {static_cast<float>(i), 0, 0};
  const PhotonMap map(std::move(line));
  EXPECT_NEAR(automaticProgressiveRadius(map, 2, 10.0f), 1.0f, 1e-6f);
  EXPECT_NEAR(automaticProgressiveRadius(map, 2, 0.5f), 0.5f, 1e-6f);  // capped
  EXPECT_EQ(automaticProgressiveRadius(PhotonMap({}), 2, 0.5f), 0.5f);
}

}  // namespace
}  // namespace prism
