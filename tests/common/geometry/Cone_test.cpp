#include "geometry/Cone.h"

#include <gtest/gtest.h>

#include "math/Random.h"
#include "math/RayOffset.h"

namespace prism {
namespace {

Cone makeCone(Vec3 base, float r0, Vec3 apex, float r1) {
  return Cone(base, r0, apex, r1, 0);
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

TEST(Cone, SurfacePointLiesOnTheSurfaceWithNormalAtsNormal) {
  // A slanted cone; points pushed off its surface come back onto it, within their error bound.
  const Vec3 base{3.0f, -1.0f, 2.0f}, apex{3.4f, 4.0f, 2.3f};
  const Cone cone = makeCone(base, 0.9f, apex, 0.3f);
  const Vec3 axis = glm::normalize(apex - base);
  Pcg32 rng(5, 1);
  for (int i = 0; i < 1000; ++i) {
    const Ray ray{Vec3(20.0f * rng.nextFloat() - 10.0f, 1.5f, 12.0f),
                  glm::normalize(Vec3(0.0f, 0.0f, 0.0f) + base + 5.0f * rng.nextFloat() * axis -
                                 Vec3(20.0f * rng.nextFloat() - 10.0f, 1.5f, 12.0f))};
    float t;
    if (!cone.intersect(ray, 1e30f, t)) continue;
    Vec3 error, normal;
    const Vec3 p = cone.surfacePoint(ray.at(t), error, normal);
    const Vec3 expected = cone.normalAt(p);
    EXPECT_NEAR(glm::length(normal - expected), 0.0f, 4e-6f) << i;  // a few roundings
    // Distance from the surface, in double: radial distance minus the radius at that height.
    const glm::dvec3 rel = glm::dvec3(p) - glm::dvec3(base);
    const double z = glm::dot(rel, glm::dvec3(axis));
    const double radial = glm::length(rel - z * glm::dvec3(axis));
    const double radius = 0.9 + (0.3 - 0.9) * z / glm::length(glm::dvec3(apex) - glm::dvec3(base));
    EXPECT_LE(std::fabs(radial - radius) * glm::length(glm::dvec3(normal)),
              static_cast<double>(glm::length(error)) + 1e-9)
        << i;
  }
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

TEST(Cone, DistantRaysLandOnTheSurfaceSoShadowRaysDoNotSelfIntersect) {
  // A thin tilted cone seen from 40 units away: in single precision the discriminant loses
  // enough digits to put hit points inside the surface, and shadow rays then hit the cone itself.
  const Vec3 base{3.0f, -1.0f, 2.0f}, apex{3.4f, 4.0f, 2.3f};
  const Cone cone = makeCone(base, 0.12f, apex, 0.05f);
  Pcg32 rng(17, 5);
  int hits = 0, selfShadowed = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 target = glm::mix(base, apex, rng.nextFloat()) +
                        0.15f * Vec3(rng.nextFloat() - 0.5f, 0.0f, rng.nextFloat() - 0.5f);
    const Vec3 eye(-30.0f, 20.0f, 25.0f);
    const Ray primary{eye, glm::normalize(target - eye)};
    float t;
    if (!cone.intersect(primary, 1e30f, t)) continue;
    Vec3 error, n;
    const Vec3 p = cone.surfacePoint(primary.at(t), error, n);
    // Only the outside: from the inside the opposite wall may rightly block the light.
    if (glm::dot(n, primary.direction) > 0.0f) continue;
    ++hits;
    // A light on the viewer's side of the surface, in a random direction.
    Vec3 l = glm::normalize(
        Vec3(rng.nextFloat() - 0.5f, rng.nextFloat() - 0.5f, rng.nextFloat() - 0.5f));
    if (glm::dot(l, n) < 0.0f) l = -l;
    const Ray shadow{leavingOrigin(p, n, leavingDistance(p, error, n), l), l, 0.0f, 100.0f};
    if (cone.intersect(shadow, shadow.tMax, t)) ++selfShadowed;
  }
  EXPECT_GT(hits, 5000);
  EXPECT_EQ(selfShadowed, 0) << "of " << hits << " hits";
}

}  // namespace
}  // namespace prism
