#include "shading/Optics.h"

#include <gtest/gtest.h>

namespace prism {
namespace {

TEST(Optics, FresnelAtNormalIncidenceIsTheTextbookValue) {
  // ((n1 − n2) / (n1 + n2))² = 0.04 for air to glass of index 1.5.
  EXPECT_NEAR(fresnelDielectric(1.0f, 1.0f / 1.5f), 0.04f, 1e-6f);
  EXPECT_NEAR(fresnelDielectric(1.0f, 1.5f), 0.04f, 1e-6f);
}

TEST(Optics, FresnelAtGrazingIncidenceIsTotal) {
  EXPECT_NEAR(fresnelDielectric(1e-6f, 1.0f / 1.5f), 1.0f, 1e-4f);
}

TEST(Optics, BrewsterAngleHasNoParallelReflection) {
  // At Brewster's angle only the s polarisation reflects: R = rs²/2.
  const float n = 1.5f;
  const float thetaB = std::atan(n);
  const float cosI = std::cos(thetaB);
  const float cosT = std::cos(std::asin(std::sin(thetaB) / n));
  const float rs = (cosI - n * cosT) / (cosI + n * cosT);
  EXPECT_NEAR(fresnelDielectric(cosI, 1.0f / n), 0.5f * rs * rs, 1e-6f);
}

TEST(Optics, TotalInternalReflectionBeyondTheCriticalAngle) {
  const float n = 1.5f;
  const float critical = std::asin(1.0f / n);  // 41.8°
  const Vec3 normal(0, 0, 1);                  // facing the incoming ray (inside the glass)
  for (float degrees : {42.0f, 50.0f, 80.0f}) {
    const float a = glm::radians(degrees);
    const Vec3 d(std::sin(a), 0, -std::cos(a));
    EXPECT_FALSE(refract(d, normal, n).has_value()) << degrees;
    EXPECT_FLOAT_EQ(fresnelDielectric(std::cos(a), n), 1.0f) << degrees;
  }
  const float below = critical - glm::radians(0.5f);
  const Vec3 d(std::sin(below), 0, -std::cos(below));
  EXPECT_TRUE(refract(d, normal, n).has_value());
  EXPECT_LT(fresnelDielectric(std::cos(below), n), 1.0f);
}

TEST(Optics, SnellsLawHolds) {
  const float n = 1.5f;
  const float a = glm::radians(35.0f);
  const Vec3 d(std::sin(a), 0, -std::cos(a));
  const auto t = refract(d, Vec3(0, 0, 1), 1.0f / n);
  ASSERT_TRUE(t);
  EXPECT_NEAR(glm::length(*t), 1.0f, 1e-6f);
  EXPECT_NEAR(std::sin(a), n * t->x, 1e-6f);  // sin θi = n · sin θt
  EXPECT_LT(t->z, 0.0f);
}

TEST(Optics, GlassSlabExitRayIsParallelToTheEntryRay) {
  // Through two parallel faces the direction is restored exactly (up to rounding).
  const Vec3 normal(0, 1, 0);
  for (float degrees : {0.0f, 15.0f, 40.0f, 70.0f, 89.0f}) {
    const float a = glm::radians(degrees);
    const Vec3 in = glm::normalize(Vec3(std::sin(a), -std::cos(a), 0.3f * std::sin(a)));
    const auto inside = refract(in, normal, 1.0f / 1.5f);  // enter the top face
    ASSERT_TRUE(inside);
    const auto out = refract(*inside, normal, 1.5f);  // leave through the bottom face
    ASSERT_TRUE(out) << degrees;
    EXPECT_NEAR(glm::dot(*out, in), 1.0f, 1e-5f) << degrees;
  }
}

TEST(Optics, ReflectionMirrorsAboutTheNormal) {
  const Vec3 r = reflect(glm::normalize(Vec3(1, -1, 0)), Vec3(0, 1, 0));
  EXPECT_NEAR(r.x, std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(r.y, std::sqrt(0.5f), 1e-6f);
}

}  // namespace
}  // namespace prism
