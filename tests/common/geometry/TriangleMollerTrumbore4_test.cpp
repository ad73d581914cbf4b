#include "geometry/TriangleMollerTrumbore4.h"

#include <gtest/gtest.h>

#include <cstring>

#include "KernelTesting.h"
#include "geometry/TriangleMollerTrumbore.h"
#include "math/Random.h"

namespace prism {
namespace {

using test::randomVec;
using test::sameBits;

// Each lane must reproduce the scalar test bit for bit, and the pack's pick must be the one a
// sequential scalar loop with a shrinking tMax makes.
TEST(TriangleMollerTrumbore4, LanesMatchTheScalarTestBitForBit) {
  Pcg32 rng(21, 9);
  int hits = 0;
  for (int round = 0; round < 20000; ++round) {
    Triangle tris[4];
    TrianglePack4 pack;
    const int used = 1 + round % 4;  // partly filled packs too
    for (int lane = 0; lane < used; ++lane) {
      const Vec3 a = randomVec(rng, -1, 1), b = randomVec(rng, -1, 1), c = randomVec(rng, -1, 1);
      tris[lane] = {a, b, c, 0, 0};
      if (round % 7 == 0 && lane == 1) tris[lane] = tris[0];  // an exact tie
      pack.set(lane, tris[lane], static_cast<uint32_t>(lane));
    }
    Ray ray{randomVec(rng, -3, 3), glm::normalize(randomVec(rng, -1, 1))};
    ray.direction = glm::normalize(-ray.origin + 0.3f * randomVec(rng, -1, 1));
    const float tMax = (round % 5 == 0) ? 2.0f : std::numeric_limits<float>::infinity();

    int expectedLane = -1;
    float bestT = tMax, bestU = 0, bestV = 0;
    for (int lane = 0; lane < used; ++lane) {
      float t, u, v;
      if (intersectMollerTrumbore(ray, tris[lane].v0, tris[lane].edge1(), tris[lane].edge2(), bestT,
                                  t, u, v)) {
        expectedLane = lane;
        bestT = t;
        bestU = u;
        bestV = v;
      }
    }
    const PackHit got = closestInPack(ray, pack, tMax);
    ASSERT_EQ(got.lane, expectedLane) << round;
    if (expectedLane >= 0) {
      ++hits;
      ASSERT_TRUE(sameBits(got.t, bestT) && sameBits(got.u, bestU) && sameBits(got.v, bestV))
          << round;
    }
  }
  EXPECT_GT(hits, 2000);
}

TEST(TriangleMollerTrumbore4, EmptyLanesAreNeverHit) {
  const TrianglePack4 pack;
  const Ray ray{Vec3(0, 0, -1), Vec3(0, 0, 1)};
  simd::Float4 t, u, v;
  EXPECT_EQ(intersectMollerTrumbore4(ray, pack, 10.0f, t, u, v), 0u);
}

}  // namespace
}  // namespace prism
