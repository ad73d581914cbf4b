#include "geometry/ConeSegments.h"

#include <gtest/gtest.h>

#include <bit>

#include "math/Random.h"

namespace prism {
namespace {

// The nearest hit over the parts, as the BVH's closest-hit walk finds it.
bool intersectParts(const std::vector<Cone>& parts, const Ray& ray, float& t) {
  bool found = false;
  float tMax = ray.tMax;
  for (const Cone& part : parts) {
    float tPart;
    if (part.intersect(ray, tMax, tPart)) {
      tMax = tPart;
      found = true;
    }
  }
  t = tMax;
  return found;
}

Vec3 randomPoint(Pcg32& rng, float spread) {
  return spread * Vec3(rng.nextFloat() - 0.5f, rng.nextFloat() - 0.5f, rng.nextFloat() - 0.5f);
}

TEST(ConeSegments, AnAxisAlignedCylinderStaysWhole) {
  // Its box is already tight: cutting it only adds entries.
  const Cone cylinder({0, 0, 0}, 0.1f, {0, 0, 5}, 0.1f, 0);
  EXPECT_EQ(bvhParts(cylinder).size(), 1u);
}

TEST(ConeSegments, AShortSlantedConeStaysWhole) {
  const Cone stub({0, 0, 0}, 1.0f, {0.3f, 0.3f, 0.3f}, 1.0f, 0);
  EXPECT_EQ(bvhParts(stub).size(), 1u);
}

TEST(ConeSegments, ALongSlantedCylinderIsCutIntoTighterBoxes) {
  // An SPD rings-style segment: length 1.1, radius 0.074, at 45 degrees.
  const Cone cylinder({0.93f, 2.61f, 0}, 0.074f, {0.29f, 3.50f, 0}, 0.074f, 0);
  const std::vector<Cone> parts = bvhParts(cylinder);
  ASSERT_GT(parts.size(), 1u);
  float area = 0.0f;
  for (const Cone& part : parts) area += part.bounds().surfaceArea();
  EXPECT_LT(area, 0.8f * cylinder.bounds().surfaceArea());
}

TEST(ConeSegments, PartsHitWhereTheWholeConeHitsWithTheSameT) {
  // Rays aimed at and around slanted cones, cylinders and pointed cones, from near and far:
  // the parts' nearest hit is the whole cone's, bit for bit, and they miss where it misses.
  const Cone cones[] = {
      Cone({0.93f, 2.61f, 0}, 0.074f, {0.29f, 3.50f, 0}, 0.074f, 0),
      Cone({1, 2, 3}, 0.5f, {6, -4, 9}, 0.1f, 0),
      Cone({-2, 0, 1}, 0.3f, {3, 4, -2}, 0.0f, 0),
  };
  Pcg32 rng(41, 3);
  for (const Cone& cone : cones) {
    const std::vector<Cone> parts = bvhParts(cone);
    ASSERT_GT(parts.size(), 1u);
    const Aabb box = cone.bounds();
    int hits = 0;
    for (int i = 0; i < 50000; ++i) {
      const float distance = i % 2 ? 3.0f : 300.0f;
      const Vec3 target =
          box.lower + Vec3(rng.nextFloat(), rng.nextFloat(), rng.nextFloat()) * box.extent();
      const Vec3 origin = box.center() + randomPoint(rng, distance);
      const Ray ray{origin, glm::normalize(target - origin)};
      float tWhole = 0.0f, tParts = 0.0f;
      const bool whole = cone.intersect(ray, ray.tMax, tWhole);
      ASSERT_EQ(intersectParts(parts, ray, tParts), whole) << "ray " << i;
      if (!whole) continue;
      ++hits;
      ASSERT_EQ(std::bit_cast<uint32_t>(tParts), std::bit_cast<uint32_t>(tWhole)) << "ray " << i;
    }
    EXPECT_GT(hits, 2000);
  }
}

TEST(ConeSegments, EachPartsBoxHoldsItsSurfaceAndTheHitsInIt) {
  const Cone cone({1, 2, 3}, 0.5f, {6, -4, 9}, 0.1f, 0);
  const std::vector<Cone> parts = bvhParts(cone);
  Pcg32 rng(7, 11);
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 origin = cone.bounds().center() + randomPoint(rng, 40.0f);
    const Vec3 target =
        cone.bounds().lower +
        Vec3(rng.nextFloat(), rng.nextFloat(), rng.nextFloat()) * cone.bounds().extent();
    const Ray ray{origin, glm::normalize(target - origin)};
    for (const Cone& part : parts) {
      float t;
      if (!part.intersect(ray, ray.tMax, t)) continue;
      ++hits;
      const Vec3 p = ray.at(t);
      const Aabb box = part.bounds();
      for (int j = 0; j < 3; ++j) {
        EXPECT_GE(p[j], box.lower[j] - 1e-4f);
        EXPECT_LE(p[j], box.upper[j] + 1e-4f);
      }
    }
  }
  EXPECT_GT(hits, 1000);
}

}  // namespace
}  // namespace prism
