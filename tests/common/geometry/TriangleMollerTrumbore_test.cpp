#include "geometry/TriangleMollerTrumbore.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "TestMeshes.h"
#include "geometry/TrianglePlaneInside.h"
#include "geometry/TriangleWatertight.h"
#include "math/Random.h"

namespace prism {
namespace {

// An intersector given the triangle's three vertices.
using Intersector = bool (*)(const Ray&, const Vec3&, const Vec3&, const Vec3&, float, float&,
                             float&, float&);

bool mollerTrumbore(const Ray& r, const Vec3& a, const Vec3& b, const Vec3& c, float tMax, float& t,
                    float& u, float& v) {
  return intersectMollerTrumbore(r, a, b - a, c - a, tMax, t, u, v);
}

bool planeThenInside(const Ray& r, const Vec3& a, const Vec3& b, const Vec3& c, float tMax,
                     float& t, float& u, float& v) {
  return intersectPlaneThenInside(r, a, b - a, c - a, tMax, t, u, v);
}

bool watertight(const Ray& r, const Vec3& a, const Vec3& b, const Vec3& c, float tMax, float& t,
                float& u, float& v) {
  return intersectWatertight(r, a, b, c, tMax, t, u, v);
}

TEST(MollerTrumbore, HitsTriangleWithExpectedDistanceAndBarycentrics) {
  const Vec3 v0(0, 0, 0), v1(1, 0, 0), v2(0, 1, 0);
  float t, u, v;
  ASSERT_TRUE(intersectMollerTrumbore(Ray{{0.25f, 0.5f, 2}, {0, 0, -1}}, v0, v1 - v0, v2 - v0,
                                      1e30f, t, u, v));
  EXPECT_FLOAT_EQ(t, 2.0f);
  EXPECT_FLOAT_EQ(u, 0.25f);
  EXPECT_FLOAT_EQ(v, 0.5f);
}

TEST(MollerTrumbore, TwoSidedAndRejectsParallelAndOutside) {
  const Vec3 v0(0, 0, 0), e1(1, 0, 0), e2(0, 1, 0);
  float t, u, v;
  EXPECT_TRUE(
      intersectMollerTrumbore(Ray{{0.2f, 0.2f, -1}, {0, 0, 1}}, v0, e1, e2, 1e30f, t, u, v));
  EXPECT_FALSE(
      intersectMollerTrumbore(Ray{{0.2f, 0.2f, 1}, {1, 0, 0}}, v0, e1, e2, 1e30f, t, u, v));
  EXPECT_FALSE(
      intersectMollerTrumbore(Ray{{0.8f, 0.8f, 1}, {0, 0, -1}}, v0, e1, e2, 1e30f, t, u, v));
}

TEST(MollerTrumbore, SmallTrianglesAreNotRejectedByAnAbsoluteEpsilon) {
  // det = 1e-12 here: the paper's |det| < 1e-6 test would miss this triangle.
  const Vec3 v0(0, 0, 0), e1(1e-4f, 0, 0), e2(0, 1e-4f, 0);
  float t, u, v;
  EXPECT_TRUE(
      intersectMollerTrumbore(Ray{{2e-5f, 2e-5f, 1e-4f}, {0, 0, -1}}, v0, e1, e2, 1e30f, t, u, v));
}

TEST(TriangleIntersectors, AgreeAwayFromEdges) {
  Pcg32 rng(7, 1);
  auto uniform = [&](float lo, float hi) { return lo + (hi - lo) * rng.nextFloat(); };
  int compared = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 v0(uniform(-2, 2), uniform(-2, 2), uniform(-2, 2));
    const Vec3 e1(uniform(-2, 2), uniform(-2, 2), uniform(-2, 2));
    const Vec3 e2(uniform(-2, 2), uniform(-2, 2), uniform(-2, 2));
    if (glm::length(glm::cross(e1, e2)) < 1e-2f) continue;
    // Aim at a barycentric point at least 0.05 from every edge, or clearly outside.
    float a = uniform(-0.5f, 1.5f), b = uniform(-0.5f, 1.5f);
    const float c = 1.0f - a - b;
    const float edgeDistance = std::min(std::min(std::fabs(a), std::fabs(b)), std::fabs(c));
    if (edgeDistance < 0.05f) continue;
    const Vec3 target = v0 + a * e1 + b * e2;
    const Vec3 origin = target + Vec3(uniform(-5, 5), uniform(-5, 5), uniform(-5, 5));
    const Ray ray{origin, glm::normalize(target - origin)};
    if (std::fabs(glm::dot(ray.direction, glm::normalize(glm::cross(e1, e2)))) < 0.05f) continue;
    float t1, u1, w1, t2, u2, w2;
    const bool hit1 = intersectMollerTrumbore(ray, v0, e1, e2, 1e30f, t1, u1, w1);
    const bool hit2 = intersectPlaneThenInside(ray, v0, e1, e2, 1e30f, t2, u2, w2);
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

// Shoots rays from inside a closed mesh at points exactly on its shared edges and vertices and
// counts the rays that slip through (hit no triangle). Returns the fraction that cracked.
double crackRate(Intersector intersect, int* raysOut) {
  const test::TestMesh mesh = test::icosphere(3, Vec3(3.1f, -2.7f, 5.3f), 1.7f);
  const Vec3 inside = Vec3(3.1f, -2.7f, 5.3f) + Vec3(0.13f, -0.07f, 0.21f);
  Pcg32 rng(11, 3);
  int rays = 0, cracks = 0;
  auto shoot = [&](const Vec3& target) {
    const Ray ray{inside, glm::normalize(target - inside)};
    bool hit = false;
    for (size_t f = 0; f < mesh.indices.size() && !hit; f += 3) {
      const Vec3& a = mesh.positions[mesh.indices[f]];
      const Vec3& b = mesh.positions[mesh.indices[f + 1]];
      const Vec3& c = mesh.positions[mesh.indices[f + 2]];
      float t, u, v;
      hit = intersect(ray, a, b, c, 1e30f, t, u, v);
    }
    ++rays;
    if (!hit) ++cracks;
  };
  for (size_t f = 0; f < mesh.indices.size(); f += 3) {
    for (int k = 0; k < 3; ++k) {
      const Vec3& a = mesh.positions[mesh.indices[f + k]];
      const Vec3& b = mesh.positions[mesh.indices[f + (k + 1) % 3]];
      shoot(a);                                                            // vertex
      for (int s = 0; s < 8; ++s) shoot(glm::mix(a, b, rng.nextFloat()));  // edge
    }
  }
  *raysOut = rays;
  return static_cast<double>(cracks) / rays;
}

TEST(TriangleIntersectors, CrackRateOnSharedEdgesIsMeasuredAndSmall) {
  int rays = 0;
  const double mt = crackRate(mollerTrumbore, &rays);
  const double classic = crackRate(planeThenInside, &rays);
  const double tight = crackRate(watertight, &rays);
  std::printf(
      "[ crack rate ] %d rays at shared edges/vertices of a closed icosphere: "
      "Moller-Trumbore %.4f %%, plane-then-inside %.4f %%, watertight %.4f %%\n",
      rays, 100.0 * mt, 100.0 * classic, 100.0 * tight);
  RecordProperty("rays", rays);
  RecordProperty("moller_trumbore_crack_percent", std::to_string(100.0 * mt));
  RecordProperty("plane_inside_crack_percent", std::to_string(100.0 * classic));
  RecordProperty("watertight_crack_percent", std::to_string(100.0 * tight));
  // Möller–Trumbore and plane-then-inside are not watertight: rays aimed at an edge to within
  // float precision slip through both neighbours a few percent of the time (docs/stability.md
  // records the numbers). The bounds pin that down so a change in either shows up here. The
  // watertight test (Woop et al. 2013) lets none through.
  EXPECT_GT(mt, 0.0);
  EXPECT_LT(mt, 0.10);
  EXPECT_GT(classic, 0.0);
  EXPECT_LT(classic, 0.10);
  EXPECT_EQ(tight, 0.0);
}

TEST(TriangleIntersectors, RaysAwayFromEdgesNeverCrack) {
  const test::TestMesh mesh = test::icosphere(3, Vec3(0.0f), 1.0f);
  Pcg32 rng(5, 9);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 d = glm::normalize(
        Vec3(rng.nextFloat() - 0.5f, rng.nextFloat() - 0.5f, rng.nextFloat() - 0.5f));
    const Ray ray{Vec3(0.01f, 0.02f, -0.03f), d};
    int hits = 0;
    for (size_t f = 0; f < mesh.indices.size(); f += 3) {
      const Vec3& a = mesh.positions[mesh.indices[f]];
      const Vec3& b = mesh.positions[mesh.indices[f + 1]];
      const Vec3& c = mesh.positions[mesh.indices[f + 2]];
      float t, u, v;
      if (intersectMollerTrumbore(ray, a, b - a, c - a, 1e30f, t, u, v)) ++hits;
    }
    EXPECT_GE(hits, 1) << "ray " << i;
  }
}

}  // namespace
}  // namespace prism
