#include "render/MirrorLanes.h"

#include <gtest/gtest.h>

#include "common/render/LaneTestSupport.h"
#include "math/Random.h"
#include "shading/SpecularSplit.h"

namespace prism {
namespace {

// Every lane's mirror ray is reflectedDirection's direction and rayOrigin's origin to the bit,
// over 20 000 random packets: shading normals leaning far from the geometric one (so that some
// mirror directions fall below the surface and are taken about the geometric normal), and
// incoming directions from either side.
TEST(MirrorLanes, EveryLaneIsTheScalarMirrorRayBitForBit) {
  Pcg32 rng(5, 9);
  int aboutGeometric = 0, stepsBack = 0;
  for (int round = 0; round < 20000; ++round) {
    SurfaceHit points[ShadingLanes::kLanes];
    Vec3 incoming[ShadingLanes::kLanes];
    ShadingLanes s{};
    for (int i = 0; i < ShadingLanes::kLanes; ++i) {
      SurfaceHit& p = points[i];
      p.position = Vec3(10.0f * rng.nextFloat() - 5.0f, 3.0f * rng.nextFloat(), -rng.nextFloat());
      p.geometricNormal = randomUnit(rng);
      p.shadingNormal = glm::normalize(p.geometricNormal + 0.9f * randomUnit(rng));
      p.leavingDistance = 1e-5f * (1.0f + rng.nextFloat());
      incoming[i] = randomUnit(rng);
      s.set(i, p, Color(0.5f), MaterialDesc{}, -incoming[i]);
    }
    Ray rays[ShadingLanes::kLanes];
    mirrorRayLanes(s, rays);
    for (int i = 0; i < ShadingLanes::kLanes; ++i) {
      const Vec3 direction = reflectedDirection(points[i], incoming[i]);
      const Vec3 origin = points[i].rayOrigin(direction);
      ASSERT_TRUE(sameBits(rays[i].direction, direction)) << "round " << round << " lane " << i;
      ASSERT_TRUE(sameBits(rays[i].origin, origin)) << "round " << round << " lane " << i;
      EXPECT_EQ(rays[i].tMin, 0.0f);
      EXPECT_EQ(rays[i].tMax, Ray{}.tMax);
      const Vec3 aboutShading = reflect(incoming[i], points[i].shadingNormal);
      aboutGeometric += glm::dot(aboutShading, points[i].geometricNormal) > 0.0f ? 0 : 1;
      stepsBack += glm::dot(direction, points[i].geometricNormal) < 0.0f ? 1 : 0;
    }
  }
  // Both branches of each choice were taken often.
  EXPECT_GT(aboutGeometric, 10000);
  EXPECT_GT(stepsBack, 10000);
}

}  // namespace
}  // namespace prism
