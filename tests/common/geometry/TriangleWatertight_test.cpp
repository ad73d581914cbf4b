#include "geometry/TriangleWatertight.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "TestMeshes.h"
#include "geometry/TriangleMollerTrumbore.h"
#include "math/Random.h"

namespace prism {
namespace {

bool hitWatertight(const Ray& ray, const Vec3& a, const Vec3& b, const Vec3& c, float& t, float& u,
                   float& v) {
  return intersectWatertight(ray, a, b, c, 1e30f, t, u, v);
}

TEST(Watertight, HitsTriangleWithExpectedDistanceAndBarycentrics) {
  const Vec3 v0(0, 0, 0), v1(1, 0, 0), v2(0, 1, 0);
  float t, u, v;
  ASSERT_TRUE(hitWatertight(Ray{{0.25f, 0.5f, 2}, {0, 0, -1}}, v0, v1, v2, t, u, v));
  EXPECT_FLOAT_EQ(t, 2.0f);
  EXPECT_FLOAT_EQ(u, 0.25f);
  EXPECT_FLOAT_EQ(v, 0.5f);
  // Every permutation of the dominant axis and both signs of it.
  const Vec3 p0(1, 2, 3), p1(4, 2.5f, 3.5f), p2(2, 5, 2);
  const Vec3 target = p0 + 0.2f * (p1 - p0) + 0.3f * (p2 - p0);
  for (const Vec3 offset : {Vec3(9, 1, 2), Vec3(-9, 1, 2), Vec3(1, 9, -2), Vec3(1, -9, 2),
                            Vec3(2, 1, 9), Vec3(-2, 1, -9)}) {
    const Vec3 origin = target + offset;
    const Ray ray{origin, glm::normalize(target - origin)};
    ASSERT_TRUE(hitWatertight(ray, p0, p1, p2, t, u, v)) << offset.x << offset.y << offset.z;
    EXPECT_NEAR(t, glm::length(offset), 1e-5f);
    EXPECT_NEAR(u, 0.2f, 1e-5f);
    EXPECT_NEAR(v, 0.3f, 1e-5f);
  }
}

TEST(Watertight, TwoSidedAndRejectsParallelOutsideAndOutOfRange) {
  const Vec3 v0(0, 0, 0), v1(1, 0, 0), v2(0, 1, 0);
  float t, u, v;
  EXPECT_TRUE(hitWatertight(Ray{{0.2f, 0.2f, -1}, {0, 0, 1}}, v0, v1, v2, t, u, v));
  EXPECT_TRUE(hitWatertight(Ray{{0.2f, 0.2f, 1}, {0, 0, -1}}, v0, v1, v2, t, u, v));
  EXPECT_FALSE(hitWatertight(Ray{{0.2f, 0.2f, 1}, {1, 0, 0}}, v0, v1, v2, t, u, v));
  EXPECT_FALSE(hitWatertight(Ray{{0.8f, 0.8f, 1}, {0, 0, -1}}, v0, v1, v2, t, u, v));
  EXPECT_FALSE(hitWatertight(Ray{{0.2f, 0.2f, 1}, {0, 0, 1}}, v0, v1, v2, t, u, v));  // behind
  EXPECT_FALSE(intersectWatertight(Ray{{0.2f, 0.2f, 1}, {0, 0, -1}}, v0, v1, v2, 0.5f, t, u, v));
  // A degenerate triangle (all three on a line) is never hit, even by a ray through the line.
  EXPECT_FALSE(hitWatertight(Ray{{0.5f, 0, 1}, {0, 0, -1}}, v0, v1, Vec3(2, 0, 0), t, u, v));
}

TEST(Watertight, SmallTrianglesAreNotRejectedByAnAbsoluteEpsilon) {
  const Vec3 v0(0, 0, 0), v1(1e-4f, 0, 0), v2(0, 1e-4f, 0);
  float t, u, v;
  EXPECT_TRUE(hitWatertight(Ray{{2e-5f, 2e-5f, 1e-4f}, {0, 0, -1}}, v0, v1, v2, t, u, v));
}

TEST(Watertight, AgreesWithMollerTrumboreAwayFromEdges) {
  Pcg32 rng(7, 1);
  auto uniform = [&](float lo, float hi) { return lo + (hi - lo) * rng.nextFloat(); };
  int compared = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 v0(uniform(-2, 2), uniform(-2, 2), uniform(-2, 2));
    const Vec3 v1 = v0 + Vec3(uniform(-2, 2), uniform(-2, 2), uniform(-2, 2));
    const Vec3 v2 = v0 + Vec3(uniform(-2, 2), uniform(-2, 2), uniform(-2, 2));
    const Vec3 e1 = v1 - v0, e2 = v2 - v0;
    if (glm::length(glm::cross(e1, e2)) < 1e-2f) continue;
    float a = uniform(-0.5f, 1.5f), b = uniform(-0.5f, 1.5f);
    const float c = 1.0f - a - b;
    if (std::min(std::min(std::fabs(a), std::fabs(b)), std::fabs(c)) < 0.05f) continue;
    const Vec3 target = v0 + a * e1 + b * e2;
    const Vec3 origin = target + Vec3(uniform(-5, 5), uniform(-5, 5), uniform(-5, 5));
    const Ray ray{origin, glm::normalize(target - origin)};
    if (std::fabs(glm::dot(ray.direction, glm::normalize(glm::cross(e1, e2)))) < 0.05f) continue;
    float t1, u1, w1, t2, u2, w2;
    const bool hit1 = intersectMollerTrumbore(ray, v0, e1, e2, 1e30f, t1, u1, w1);
    const bool hit2 = hitWatertight(ray, v0, v1, v2, t2, u2, w2);
    ASSERT_EQ(hit1, hit2) << "case " << i;
    if (hit1) {
      EXPECT_NEAR(t1, t2, 1e-3f * std::max(1.0f, t1));
      EXPECT_NEAR(u1, u2, 1e-3f);
      EXPECT_NEAR(w1, w2, 1e-3f);
    }
    ++compared;
  }
  EXPECT_GT(compared, 5000);
}

// Rays from many origins at points exactly on the shared edges and vertices of closed meshes
// placed far from the origin and at very different scales: not one may slip through.
TEST(Watertight, NoRayThroughAClosedMeshEscapesAtAnyScale) {
  Pcg32 rng(3, 17);
  int rays = 0, cracks = 0;
  for (const float scale : {1e-3f, 1.0f, 1e3f, 1e5f}) {
    const Vec3 centre = scale * Vec3(3.1f, -2.7f, 5.3f);
    const test::TestMesh mesh = test::icosphere(2, centre, 1.7f * scale);
    for (int o = 0; o < 4; ++o) {
      const Vec3 inside = centre + scale * Vec3(rng.nextFloat() - 0.5f, rng.nextFloat() - 0.5f,
                                                rng.nextFloat() - 0.5f);
      for (size_t f = 0; f < mesh.indices.size(); f += 3) {
        for (int k = 0; k < 3; ++k) {
          const Vec3& a = mesh.positions[mesh.indices[f + k]];
          const Vec3& b = mesh.positions[mesh.indices[f + (k + 1) % 3]];
          for (int s = 0; s < 5; ++s) {
            const Vec3 target = s == 0 ? a : glm::mix(a, b, rng.nextFloat());
            const Ray ray{inside, glm::normalize(target - inside)};
            bool hit = false;
            for (size_t g = 0; g < mesh.indices.size() && !hit; g += 3) {
              float t, u, v;
              hit = hitWatertight(ray, mesh.positions[mesh.indices[g]],
                                  mesh.positions[mesh.indices[g + 1]],
                                  mesh.positions[mesh.indices[g + 2]], t, u, v);
            }
            ++rays;
            if (!hit) ++cracks;
          }
        }
      }
    }
  }
  EXPECT_EQ(cracks, 0) << "of " << rays << " rays";
}

// Two triangles sharing an edge, rays exactly through points of that edge's line in the sheared
// frame: edge functions that round to zero go to the double-precision recomputation.
TEST(Watertight, RaysAlongASharedEdgeHitOneOfItsTriangles) {
  const Vec3 a(0, 0, 0), b(1, 1, 0), c(1, 0, 0), d(0, 1, 0);
  int hits = 0;
  for (int i = 0; i <= 64; ++i) {
    const float s = i / 64.0f;
    const Ray ray{Vec3(s, s, 5), Vec3(0, 0, -1)};  // exactly over the diagonal a–b
    float t, u, v;
    const bool first = hitWatertight(ray, a, b, c, t, u, v);
    const bool second = hitWatertight(ray, b, a, d, t, u, v);
    EXPECT_TRUE(first || second) << s;
    hits += first && second;  // inclusive edges: both report it
  }
  EXPECT_EQ(hits, 65);
}

}  // namespace
}  // namespace prism
