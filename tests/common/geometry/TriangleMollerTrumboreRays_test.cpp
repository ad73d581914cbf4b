#include "geometry/TriangleMollerTrumboreRays.h"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>

#include "KernelTesting.h"
#include "geometry/Triangle.h"
#include "geometry/TriangleMollerTrumbore.h"
#include "math/Random.h"

namespace prism {
namespace {

using test::randomVec;
using test::sameBits;

template <class V>
class TriangleMollerTrumboreRays : public ::testing::Test {};
using LaneTypes = ::testing::Types<simd::Float4, simd::Float8>;
TYPED_TEST_SUITE(TriangleMollerTrumboreRays, LaneTypes);

// Each ray's lane must reproduce the scalar test bit for bit: whether it hits, and t, u, v.
TYPED_TEST(TriangleMollerTrumboreRays, LanesMatchTheScalarTestBitForBit) {
  using V = TypeParam;
  constexpr int kLanes = sizeof(V) / sizeof(float);
  Pcg32 rng(31, 7);
  int hits = 0, misses = 0;
  for (int round = 0; round < 20000; ++round) {
    const Vec3 a = randomVec(rng, -1, 1), b = randomVec(rng, -1, 1);
    // Every eighth triangle degenerate (det exactly 0 for every ray): never hit.
    const Vec3 c = round % 8 == 0 ? a + 2.0f * (b - a) : randomVec(rng, -1, 1);
    const Triangle tri{a, b, c, 0, 0};
    const Vec3 e1 = tri.edge1(), e2 = tri.edge2();
    const float v0[3] = {a.x, a.y, a.z}, edge1[3] = {e1.x, e1.y, e1.z},
                edge2[3] = {e2.x, e2.y, e2.z};
    Ray rays[kLanes];
    RayLanes<V> lanes;
    V tMax;
    for (int i = 0; i < kLanes; ++i) {
      rays[i].origin = randomVec(rng, -3, 3);
      rays[i].direction = glm::normalize(-rays[i].origin + 0.3f * randomVec(rng, -1, 1));
      rays[i].tMin = (round + i) % 3 == 0 ? 1.5f : 0.0f;
      tMax[i] = (round + i) % 5 == 0 ? 2.0f : std::numeric_limits<float>::infinity();
      lanes.ox[i] = rays[i].origin.x;
      lanes.oy[i] = rays[i].origin.y;
      lanes.oz[i] = rays[i].origin.z;
      lanes.dx[i] = rays[i].direction.x;
      lanes.dy[i] = rays[i].direction.y;
      lanes.dz[i] = rays[i].direction.z;
      lanes.tMin[i] = rays[i].tMin;
    }
    V t, u, v;
    simd::MaskOf<V> inside;
    const uint32_t mask =
        intersectMollerTrumboreRays(lanes, v0, edge1, edge2, tMax, t, u, v, inside);
    for (int i = 0; i < kLanes; ++i) {
      float tHit, uHit, vHit;
      const bool expected = intersectMollerTrumbore(rays[i], a, e1, e2, tMax[i], tHit, uHit, vHit);
      ASSERT_EQ((mask >> i & 1u) != 0, expected) << round << " lane " << i;
      ASSERT_EQ(inside[i] != 0, expected) << round << " lane " << i;
      if (!expected) {
        ++misses;
        continue;
      }
      ++hits;
      ASSERT_TRUE(sameBits(t[i], tHit) && sameBits(u[i], uHit) && sameBits(v[i], vHit)) << round;
    }
  }
  EXPECT_GT(hits, 2000 * kLanes);
  EXPECT_GT(misses, 2000 * kLanes);
}

// A lane whose tMax is -inf (a ray the packet leaves out) is never hit, even dead ahead.
TEST(TriangleMollerTrumboreRaysFour, ALaneLookingNowhereIsNeverHit) {
  const float v0[3] = {-1, -1, 0}, e1[3] = {2, 0, 0}, e2[3] = {0, 2, 0};
  RayLanes<simd::Float4> lanes{};
  lanes.oz = simd::broadcast<simd::Float4>(-1.0f);
  lanes.dz = simd::broadcast<simd::Float4>(1.0f);
  const float inf = std::numeric_limits<float>::infinity();
  const simd::Float4 tMax{inf, -inf, inf, -inf};
  simd::Float4 t, u, v;
  simd::Int4 inside;
  EXPECT_EQ(intersectMollerTrumboreRays(lanes, v0, e1, e2, tMax, t, u, v, inside), 0b0101u);
  EXPECT_EQ(t[0], 1.0f);
}

}  // namespace
}  // namespace prism
