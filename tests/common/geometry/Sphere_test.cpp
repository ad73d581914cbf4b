#include "geometry/Sphere.h"

#include <gtest/gtest.h>

namespace prism {
namespace {

Ray rayFrom(Vec3 origin, Vec3 direction) {
  return Ray{origin, glm::normalize(direction)};
}

TEST(Sphere, HitsNearSideFromOutside) {
  const Sphere s{{0, 0, 0}, 1.0f, 0};
  float t;
  ASSERT_TRUE(s.intersect(rayFrom({0, 0, 5}, {0, 0, -1}), 1e30f, t));
  EXPECT_FLOAT_EQ(t, 4.0f);
}

TEST(Sphere, HitsFarSideFromInside) {
  const Sphere s{{0, 0, 0}, 2.0f, 0};
  float t;
  ASSERT_TRUE(s.intersect(rayFrom({0, 0, 0}, {1, 0, 0}), 1e30f, t));
  EXPECT_FLOAT_EQ(t, 2.0f);
}

TEST(Sphere, MissesAndRespectsInterval) {
  const Sphere s{{0, 0, 0}, 1.0f, 0};
  float t;
  EXPECT_FALSE(s.intersect(rayFrom({0, 2, 5}, {0, 0, -1}), 1e30f, t));
  EXPECT_FALSE(s.intersect(rayFrom({0, 0, 5}, {0, 0, 1}), 1e30f, t));  // behind the ray
  EXPECT_FALSE(s.intersect(rayFrom({0, 0, 5}, {0, 0, -1}), 3.5f, t));  // beyond tMax
}

TEST(Sphere, SmallSphereFarAwayKeepsItsHit) {
  // Cancellation in the textbook quadratic loses this hit in single precision.
  const Sphere s{{0, 0, -10000}, 0.01f, 0};
  float t;
  ASSERT_TRUE(s.intersect(rayFrom({0, 0, 0}, {0, 0, -1}), 1e30f, t));
  EXPECT_NEAR(t, 9999.99f, 1e-2f);
}

TEST(Sphere, TangentRayGrazesOrMissesWithoutNaN) {
  const Sphere s{{0, 0, 0}, 1.0f, 0};
  float t = -1.0f;
  const bool hit = s.intersect(rayFrom({1, 0, 5}, {0, 0, -1}), 1e30f, t);
  // Either answer is acceptable for an exactly tangent ray; a hit must be at the tangent point.
  if (hit) {
    EXPECT_NEAR(t, 5.0f, 1e-3f);
  }
}

}  // namespace
}  // namespace prism
