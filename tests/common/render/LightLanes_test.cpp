#include "render/LightLanes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/render/LaneTestSupport.h"
#include "math/Random.h"
#include "render/PointLightPath.h"

namespace prism {
namespace {

// A shading point of every kind the lanes must tell apart: lit from the front, behind its
// geometric or its shading normal, at the light itself, with NaN normals (a degenerate
// triangle), with a highlight that underflows, faces away or counts, with or without a diffuse
// albedo or a specular colour.
struct RandomPoint {
  SurfaceHit surface;
  Color albedo{0.0f};
  MaterialDesc material;
  Vec3 toViewer{0.0f};
};

RandomPoint randomPoint(Pcg32& rng, const Vec3& lightPosition) {
  RandomPoint p;
  const int kind = static_cast<int>(rng.nextFloat() * 10.0f);
  p.surface.position = Vec3(4.0f * rng.nextFloat() - 2.0f, 3.0f * rng.nextFloat() - 1.0f,
                            4.0f * rng.nextFloat() - 2.0f);
  if (kind == 0) p.surface.position = lightPosition;
  p.surface.geometricNormal = randomUnit(rng);
  p.surface.shadingNormal = glm::normalize(p.surface.geometricNormal + 0.4f * randomUnit(rng));
  if (kind == 1) p.surface.geometricNormal = Vec3(std::numeric_limits<float>::quiet_NaN());
  if (kind == 2) p.surface.shadingNormal = Vec3(std::numeric_limits<float>::quiet_NaN());
  p.surface.leavingDistance = 1e-6f * (1.0f + rng.nextFloat());
  p.albedo = rng.nextFloat() < 0.5f ? Color(0.0f) : Color(rng.nextFloat(), 0.5f, 0.25f);
  if (rng.nextFloat() < 0.7f) p.material.specular = Color(0.2f + 0.8f * rng.nextFloat());
  p.material.shininess = rng.nextFloat() < 0.5f ? 400.0f : 1.0f + 60.0f * rng.nextFloat();
  p.toViewer = randomUnit(rng);
  return p;
}

// Every lane's path, shadow ray, reflectance and added light is the scalar code's to the bit,
// over 20 000 random packets of eight (some lanes left out, some packets short).
TEST(LightLanes, EveryLaneIsTheScalarPathBitForBit) {
  Pcg32 rng(11, 3);
  PointLightDesc light;
  light.position = {0.5f, 4.0f, -0.25f};
  light.intensity = {30.0f, 20.0f, 10.0f};
  light.attenuation = {0.5f, 0.25f, 1.0f};
  int traced = 0, skippedAsBlack = 0, unreachable = 0;
  for (int round = 0; round < 20000; ++round) {
    const int count = 1 + static_cast<int>(rng.nextFloat() * 8.0f) % 8;
    const uint32_t lanes = static_cast<uint32_t>(rng.nextFloat() * 256.0f) & ((1u << count) - 1u);
    RandomPoint points[ShadingLanes::kLanes];
    ShadingLanes s{};
    for (int i = 0; i < count; ++i) {
      points[i] = randomPoint(rng, light.position);
      if (lanes >> i & 1u) {
        s.set(i, points[i].surface, points[i].albedo, points[i].material, points[i].toViewer);
      }
    }
    LightPathLanes paths;
    Ray shadows[ShadingLanes::kLanes];
    for (Ray& shadow : shadows) shadow.tMin = shadow.tMax = 5.0f;  // left from a previous light
    lightPathLanes(s, lanes, count, light, paths, shadows);
    const uint32_t unblocked = paths.towards & static_cast<uint32_t>(rng.nextFloat() * 256.0f);
    alignas(32) ShadingLanes::Lanes direct[3];
    for (int c = 0; c < 3; ++c) {
      for (int i = 0; i < ShadingLanes::kLanes; ++i) direct[c][i] = 0.125f * static_cast<float>(i);
    }
    addLightLanes(paths, unblocked, light, direct);

    for (int i = 0; i < count; ++i) {
      const RandomPoint& p = points[i];
      LightPath path;
      Ray shadow;
      const bool reaches = (lanes >> i & 1u) && towardsLight(p.surface, light, path, shadow);
      const Color reflected =
          reaches ? reflectance(p.surface, p.albedo, p.material, path, p.toViewer) : Color(0.0f);
      const bool towards = reaches && !isBlack(reflected);
      ASSERT_EQ((paths.towards >> i & 1u) != 0, towards) << "round " << round << " lane " << i;
      Color expectedDirect(0.125f * static_cast<float>(i));
      if (!towards) {
        EXPECT_EQ(shadows[i].tMax, -1.0f);  // an empty ray
        EXPECT_EQ(shadows[i].tMin, 0.0f);
        (reaches ? skippedAsBlack : unreachable) += 1;
      } else {
        ++traced;
        ASSERT_TRUE(sameBits(shadows[i].origin, shadow.origin)) << round << " " << i;
        ASSERT_TRUE(sameBits(shadows[i].direction, shadow.direction)) << round << " " << i;
        ASSERT_TRUE(sameBits(shadows[i].tMin, shadow.tMin));
        ASSERT_TRUE(sameBits(shadows[i].tMax, shadow.tMax)) << round << " " << i;
        const Vec3 lanesReflectance(paths.reflectance[0][i], paths.reflectance[1][i],
                                    paths.reflectance[2][i]);
        ASSERT_TRUE(sameBits(lanesReflectance, reflected)) << round << " " << i;
        if (unblocked >> i & 1u) expectedDirect += lightReflected(light, path, reflected);
      }
      ASSERT_TRUE(sameBits(Vec3(direct[0][i], direct[1][i], direct[2][i]), expectedDirect))
          << round << " " << i;
    }
  }
  // Every case occurred often enough to count.
  EXPECT_GT(traced, 10000);
  EXPECT_GT(skippedAsBlack, 2000);
  EXPECT_GT(unreachable, 10000);
}

}  // namespace
}  // namespace prism
