#include "geometry/Cone.h"

#include <gtest/gtest.h>

namespace prism {
namespace {

Cone makeCone(Vec3 base, float r0, Vec3 apex, float r1) {
  ConeDesc d;
  d.base = base;
  d.baseRadius = r0;
  d.apex = apex;
  d.apexRadius = r1;
  return Cone(d);
}

TEST(Cone, CylinderHitFromTheSide) {
  const Cone c = makeCone({0, 0, 0}, 1.0f, {0, 2, 0}, 1.0f);
  float t;
  ASSERT_TRUE(c.intersect(Ray{{5, 1, 0}, {-1, 0, 0}}, 1e30f, t));
  EXPECT_FLOAT_EQ(t, 4.0f);
  const Vec3 n = c.normalAt({1, 1, 0});
  EXPECT_NEAR(n.x, 1.0f, 1e-6f);
  EXPECT_NEAR(n.y, 0.0f, 1e-6f);
}

TEST(Cone, OpenEndsLetAxialRaysThrough) {
  const Cone c = makeCone({0, 0, 0}, 1.0f, {0, 2, 0}, 1.0f);
  float t;
  EXPECT_FALSE(c.intersect(Ray{{0, 5, 0}, {0, -1, 0}}, 1e30f, t));
}

TEST(Cone, HitsInsideWallFromWithin) {
  const Cone c = makeCone({0, 0, 0}, 1.0f, {0, 2, 0}, 1.0f);
  float t;
  ASSERT_TRUE(c.intersect(Ray{{0, 1, 0}, {0, 0, 1}}, 1e30f, t));
  EXPECT_FLOAT_EQ(t, 1.0f);
}

TEST(Cone, TaperedRadiusMatchesHeight) {
  // Radius 1 at y = 0, 0.5 at y = 2: at y = 1 the radius is 0.75.
  const Cone c = makeCone({0, 0, 0}, 1.0f, {0, 2, 0}, 0.5f);
  float t;
  ASSERT_TRUE(c.intersect(Ray{{3, 1, 0}, {-1, 0, 0}}, 1e30f, t));
  EXPECT_NEAR(t, 3.0f - 0.75f, 1e-5f);
  // The normal tilts upwards: the surface narrows towards the apex.
  const Vec3 n = c.normalAt({0.75f, 1, 0});
  EXPECT_GT(n.y, 0.0f);
  EXPECT_NEAR(glm::length(n), 1.0f, 1e-6f);
}

TEST(Cone, PointedConeDoesNotExtendPastItsApex) {
  const Cone c = makeCone({0, 0, 0}, 1.0f, {0, 1, 0}, 0.0f);
  float t;
  EXPECT_FALSE(c.intersect(Ray{{3, 1.5f, 0}, {-1, 0, 0}}, 1e30f, t));  // mirrored nappe
  EXPECT_TRUE(c.intersect(Ray{{3, 0.5f, 0}, {-1, 0, 0}}, 1e30f, t));
  EXPECT_NEAR(t, 2.5f, 1e-5f);
}

TEST(Cone, BoundsContainTheSurface) {
  const Vec3 base(1, 2, 3), apex(2, 4, 1);
  const float r0 = 0.5f, r1 = 0.25f;
  const Cone c = makeCone(base, r0, apex, r1);
  const Aabb box = c.bounds();
  const Vec3 axis = glm::normalize(apex - base);
  Vec3 side1, side2;
  orthonormalBasis(axis, side1, side2);
  for (int i = 0; i <= 10; ++i) {
    const float h = i / 10.0f;
    const float r = r0 + (r1 - r0) * h;
    for (int k = 0; k < 64; ++k) {
      const float a = 2.0f * kPi * k / 64.0f;
      const Vec3 p = base + h * (apex - base) + r * (std::cos(a) * side1 + std::sin(a) * side2);
      for (int j = 0; j < 3; ++j) {
        EXPECT_GE(p[j], box.lower[j] - 1e-5f);
        EXPECT_LE(p[j], box.upper[j] + 1e-5f);
      }
    }
  }
}

}  // namespace
}  // namespace prism
