#include "caustics/Photon.h"

#include <gtest/gtest.h>

#include <random>

namespace prism {
namespace {

// The angle between two unit vectors from their chord, in double: acos of a dot product near 1
// loses everything below ~3e-4 rad in float.
double angleBetween(const Vec3& a, const Vec3& b) {
  const double chord = glm::length(glm::dvec3(a) - glm::dvec3(b));
  return 2.0 * std::asin(std::min(1.0, 0.5 * chord));
}

Vec3 roundTrip(const Vec3& d) {
  Photon p;
  p.setDirection(d);
  return p.directionVector();
}

TEST(Photon, IsTwentyEightBytes) {
  EXPECT_EQ(sizeof(Photon), 28u);
}

// Each 16-bit octahedral coordinate steps by 2/65535 ≈ 3.1e-5; the octahedral map stretches a
// step by at most about 2 in angle (worst near the folded edges of the z < 0 half), so the
// round trip error stays below ~7e-5 rad. 1e-4 rad (0.006°) is plenty for telling front from back.
constexpr double kMaxAngle = 1e-4;

TEST(Photon, AxesAndDiagonalsRoundTrip) {
  const Vec3 special[] = {{1, 0, 0},  {-1, 0, 0},  {0, 1, 0},    {0, -1, 0},      {0, 0, 1},
                          {0, 0, -1}, {1, 1, 1},   {-1, -1, -1}, {1, -1, -1},     {-1, 1, -1},
                          {1, 1, 0},  {-1, 0, -1}, {0, -1, 1},   {0.6f, 0, -0.8f}};
  for (const Vec3& v : special) {
    const Vec3 d = glm::normalize(v);
    const Vec3 back = roundTrip(d);
    EXPECT_NEAR(glm::length(back), 1.0f, 1e-6f);
    EXPECT_LT(angleBetween(d, back), kMaxAngle) << v.x << " " << v.y << " " << v.z;
  }
}

TEST(Photon, RandomDirectionsOnBothHemispheresRoundTrip) {
  std::mt19937 rng(7);
  std::normal_distribution<float> normal;
  double worst = 0.0;
  int below = 0;
  for (int i = 0; i < 200000; ++i) {
    const Vec3 d = glm::normalize(Vec3(normal(rng), normal(rng), normal(rng)));
    if (d.z < 0.0f) ++below;
    worst = std::max(worst, angleBetween(d, roundTrip(d)));
  }
  EXPECT_GT(below, 90000);  // both halves of the octahedron were exercised
  EXPECT_LT(worst, kMaxAngle);
}

TEST(Photon, NearlyGrazingDirectionsKeepTheirSide) {
  // What the direction is for: which side of a surface the photon came from. Directions 1e-3
  // rad from a plane, on either side, must stay on their side.
  for (float phi = 0.0f; phi < 6.28f; phi += 0.1f) {
    for (float z : {1e-3f, -1e-3f}) {
      const Vec3 d = glm::normalize(Vec3(std::cos(phi), std::sin(phi), z));
      EXPECT_EQ(roundTrip(d).z > 0.0f, z > 0.0f) << phi << " " << z;
    }
  }
}

}  // namespace
}  // namespace prism
