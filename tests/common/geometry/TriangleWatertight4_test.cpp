#include "geometry/TriangleWatertight4.h"

#include <gtest/gtest.h>

#include <cstring>

#include "KernelTesting.h"
#include "TestMeshes.h"
#include "math/Random.h"

namespace prism {
namespace {

using test::randomVec;
using test::sameBits;

// What testing the pack's triangles one after another with a shrinking tMax finds.
PackHit sequentialClosest(const Ray& ray, const Triangle* tris, int used, float tMax) {
  PackHit best;
  float bestT = tMax;
  for (int lane = 0; lane < used; ++lane) {
    float t, u, v;
    if (intersectWatertight(ray, tris[lane].v0, tris[lane].v1, tris[lane].v2, bestT, t, u, v)) {
      best = {lane, t, u, v};
      bestT = t;
    }
  }
  return best;
}

void expectSameHit(const PackHit& got, const PackHit& expected, int round) {
  ASSERT_EQ(got.lane, expected.lane) << round;
  if (expected.lane >= 0) {
    ASSERT_TRUE(sameBits(got.t, expected.t) && sameBits(got.u, expected.u) &&
                sameBits(got.v, expected.v))
        << round;
  }
}

TEST(TriangleWatertight4, LanesMatchTheScalarTestBitForBit) {
  Pcg32 rng(21, 9);
  int hits = 0;
  for (int round = 0; round < 20000; ++round) {
    Triangle tris[4];
    TrianglePack4 pack;
    const int used = 1 + round % 4;  // partly filled packs too
    for (int lane = 0; lane < used; ++lane) {
      tris[lane] = {randomVec(rng, -1, 1), randomVec(rng, -1, 1), randomVec(rng, -1, 1), 0, 0};
      if (round % 7 == 0 && lane == 1) tris[lane] = tris[0];  // an exact tie
      pack.set(lane, tris[lane], static_cast<uint32_t>(lane));
    }
    Ray ray{randomVec(rng, -3, 3), Vec3(0, 0, 1)};
    ray.direction = glm::normalize(-ray.origin + 0.3f * randomVec(rng, -1, 1));
    const float tMax = (round % 5 == 0) ? 2.0f : std::numeric_limits<float>::infinity();
    const PackHit expected = sequentialClosest(ray, tris, used, tMax);
    expectSameHit(closestInPackWatertight(ray, WatertightRay(ray.direction), pack, tMax), expected,
                  round);
    hits += expected.lane >= 0;
  }
  EXPECT_GT(hits, 2000);
}

// Rays aimed exactly at the vertices of a closed mesh, where edge functions round to zero and
// lanes take the double-precision path: the pack still answers as the scalar test does.
TEST(TriangleWatertight4, LanesOnEdgesAndVerticesMatchTheScalarTest) {
  const test::TestMesh mesh = test::icosphere(1, Vec3(0.3f, -0.2f, 0.1f), 2.0f);
  const Vec3 inside(0.25f, -0.1f, 0.05f);
  std::vector<Triangle> tris;
  for (size_t f = 0; f < mesh.indices.size(); f += 3) {
    tris.push_back({mesh.positions[mesh.indices[f]], mesh.positions[mesh.indices[f + 1]],
                    mesh.positions[mesh.indices[f + 2]], 0, 0});
  }
  int round = 0, hits = 0;
  for (const Vec3& target : mesh.positions) {
    for (const Vec3& origin : {inside, Vec3(0.0f), 3.0f * target}) {
      const Ray ray{origin, glm::normalize(target - origin)};
      for (size_t first = 0; first + 4 <= tris.size(); first += 4, ++round) {
        TrianglePack4 pack;
        for (int lane = 0; lane < 4; ++lane) pack.set(lane, tris[first + lane], 0);
        const float tMax = std::numeric_limits<float>::infinity();
        const PackHit expected = sequentialClosest(ray, &tris[first], 4, tMax);
        expectSameHit(closestInPackWatertight(ray, WatertightRay(ray.direction), pack, tMax),
                      expected, round);
        hits += expected.lane >= 0;
      }
    }
  }
  EXPECT_GT(hits, 100);
}

// Rays exactly over the diagonal two triangles share: that edge's function is exactly zero in
// float, so both lanes take the double-precision path, and both report the hit (inclusive
// edges), as the scalar test does.
TEST(TriangleWatertight4, LanesWhoseEdgeFunctionIsZeroTakeTheExactPath) {
  const Vec3 a(0, 0, 0), b(1, 1, 0), c(1, 0, 0), d(0, 1, 0);
  const Triangle tris[2] = {{a, b, c, 0, 0}, {b, a, d, 0, 0}};
  TrianglePack4 pack;
  pack.set(0, tris[0], 0);
  pack.set(1, tris[1], 1);
  for (int i = 1; i < 64; ++i) {
    const float s = i / 64.0f;
    const Ray ray{Vec3(s, s, 5), Vec3(0, 0, -1)};
    const WatertightRay sheared(ray.direction);
    simd::Float4 t, u, v;
    EXPECT_EQ(intersectWatertight4(ray, sheared, pack, 10.0f, t, u, v), 3u) << s;
    expectSameHit(closestInPackWatertight(ray, sheared, pack, 10.0f),
                  sequentialClosest(ray, tris, 2, 10.0f), i);
  }
}

TEST(TriangleWatertight4, EmptyLanesAreNeverHit) {
  const TrianglePack4 pack;
  const Ray ray{Vec3(0, 0, -1), Vec3(0, 0, 1)};
  simd::Float4 t, u, v;
  EXPECT_EQ(intersectWatertight4(ray, WatertightRay(ray.direction), pack, 10.0f, t, u, v), 0u);
}

}  // namespace
}  // namespace prism
