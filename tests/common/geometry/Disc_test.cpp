#include "geometry/Disc.h"

#include <gtest/gtest.h>

#include <cmath>

#include "math/Random.h"

namespace prism {
namespace {

Ray rayFrom(Vec3 origin, Vec3 direction) {
  return Ray{origin, glm::normalize(direction)};
}

// A disc of radius 2 around (1, 2, 3), tilted: its normal leans 30 degrees off y towards x.
DiscDesc tiltedDesc() {
  DiscDesc d;
  d.center = {1, 2, 3};
  d.normal = {std::sin(0.5236f), std::cos(0.5236f), 0};
  d.radius = 2.0f;
  return d;
}

TEST(Disc, HitsFromEitherSideAtThePlanesDistance) {
  const Disc disc = DiscDesc{{0, 0, 0}, {0, 0, 2}, 1.0f, 0, {}, {}}.shape();
  EXPECT_EQ(disc.normal, Vec3(0, 0, 1));  // normalised from the description's
  float t;
  ASSERT_TRUE(disc.intersect(rayFrom({0.5f, 0, 5}, {0, 0, -1}), 1e30f, t));
  EXPECT_FLOAT_EQ(t, 5.0f);
  ASSERT_TRUE(disc.intersect(rayFrom({0, -0.5f, -3}, {0, 0, 1}), 1e30f, t));
  EXPECT_FLOAT_EQ(t, 3.0f);
}

TEST(Disc, MissesOutsideTheRadiusBehindTheRayAndBeyondTMax) {
  const Disc disc = DiscDesc{{0, 0, 0}, {0, 0, 1}, 1.0f, 0, {}, {}}.shape();
  float t;
  EXPECT_FALSE(disc.intersect(rayFrom({1.01f, 0, 5}, {0, 0, -1}), 1e30f, t));
  EXPECT_FALSE(disc.intersect(rayFrom({0.8f, 0.8f, 5}, {0, 0, -1}), 1e30f, t));  // |p| = 1.13
  EXPECT_FALSE(disc.intersect(rayFrom({0, 0, 5}, {0, 0, 1}), 1e30f, t));         // behind
  EXPECT_FALSE(disc.intersect(rayFrom({0, 0, 5}, {0, 0, -1}), 4.5f, t));         // past tMax
  EXPECT_TRUE(disc.intersect(rayFrom({0.99f, 0, 5}, {0, 0, -1}), 1e30f, t));
}

TEST(Disc, AGrazingRayInItsPlaneMissesWithoutNaN) {
  const Disc disc = DiscDesc{{0, 0, 0}, {0, 1, 0}, 1.0f, 0, {}, {}}.shape();
  float t = -1.0f;
  EXPECT_FALSE(disc.intersect(rayFrom({-5, 0, 0}, {1, 0, 0}), 1e30f, t));
  EXPECT_EQ(t, -1.0f);
}

// Random rays at the tilted disc: each hit lies on the disc (within its radius, on its plane
// within the surface point's error bound) and inside its box; each point of the disc sampled on
// its rim is inside the box too.
TEST(Disc, HitsLieOnTheDiscAndInItsBox) {
  const DiscDesc desc = tiltedDesc();
  const Disc disc = desc.shape();
  const Aabb box = disc.bounds();
  Pcg32 rng(11, 5);
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 origin = desc.center + Vec3(rng.nextFloat() * 12 - 6, rng.nextFloat() * 12 - 6,
                                           rng.nextFloat() * 12 - 6);
    const Vec3 target = desc.center + Vec3(rng.nextFloat() * 5 - 2.5f, rng.nextFloat() * 5 - 2.5f,
                                           rng.nextFloat() * 5 - 2.5f);
    const Ray ray = rayFrom(origin, target - origin);
    float t;
    if (!disc.intersect(ray, 1e30f, t)) continue;
    ++hits;
    Vec3 error, normal;
    const Vec3 p = disc.surfacePoint(ray.at(t), error, normal);
    EXPECT_EQ(normal, disc.normal);
    EXPECT_LE(glm::length(p - desc.center), desc.radius * (1 + 1e-5f)) << i;
    const Vec3 toP = glm::dvec3(p) - glm::dvec3(desc.center);
    const double offPlane = std::abs(glm::dot(glm::dvec3(toP), glm::dvec3(disc.normal)));
    EXPECT_LE(offPlane, glm::length(glm::dvec3(error)) + 1e-6) << i;
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(p[a], box.lower[a]) << i;
      EXPECT_LE(p[a], box.upper[a]) << i;
    }
  }
  EXPECT_GT(hits, 2000);
  Vec3 side1 = glm::normalize(glm::cross(disc.normal, Vec3(0, 0, 1)));
  Vec3 side2 = glm::cross(disc.normal, side1);
  for (int k = 0; k < 360; ++k) {
    const float angle = static_cast<float>(k) * 0.01745329f;
    const Vec3 rim =
        desc.center + desc.radius * (std::cos(angle) * side1 + std::sin(angle) * side2);
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(rim[a], box.lower[a]) << k;
      EXPECT_LE(rim[a], box.upper[a]) << k;
    }
  }
  // The box is tight: on each axis, the rim's spread and the rounding allowance.
  EXPECT_NEAR(box.upper.z - box.lower.z, 2 * desc.radius, 1e-4f);
  EXPECT_NEAR(box.upper.y - box.lower.y, 2 * desc.radius * std::sin(0.5236f), 1e-4f);
}

TEST(Disc, ItsKeysRefuseWhatCannotBeADisc) {
  DiscDesc d = tiltedDesc();
  EXPECT_FALSE(shapeProblem(d).has_value());
  d.radius = 0.0f;
  ASSERT_TRUE(shapeProblem(d).has_value());
  EXPECT_EQ(shapeProblem(d)->key, "radius");
  d = tiltedDesc();
  d.normal = Vec3(0.0f);
  ASSERT_TRUE(shapeProblem(d).has_value());
  EXPECT_EQ(shapeProblem(d)->key, "normal");
  d = tiltedDesc();
  d.center.x = std::nanf("");
  ASSERT_TRUE(shapeProblem(d).has_value());
  EXPECT_EQ(shapeProblem(d)->key, "center");
}

}  // namespace
}  // namespace prism
