#include "accel/WideBvhPacket.h"

#include <gtest/gtest.h>

#include "math/Ray.h"

namespace prism {
namespace {

// Eight shadow-like rays from points `spacing` apart along x towards a light about 10 units above
// them: their lengths (tMax) are about 10. (No direction component is zero: a packet needs finite
// reciprocals.)
const Vec3 kLight(0.5f, 10.0f, 0.5f);

void shadowRays(float spacing, Ray rays[RayPacket8::kSize]) {
  const Vec3 light = kLight;
  for (int i = 0; i < RayPacket8::kSize; ++i) {
    const Vec3 from(spacing * static_cast<float>(i), 0.0f, 0.0f);
    rays[i] = {from, glm::normalize(light - from)};
    rays[i].tMax = glm::length(light - from);
  }
}

TEST(RayPacket8, ShadowRaysFromNeighbouringPointsAreCoherent) {
  Ray rays[RayPacket8::kSize];
  shadowRays(0.01f, rays);  // origins 0.07 apart, rays about 10 long
  EXPECT_TRUE(RayPacket8(rays, 0xFFu).coherent);
}

// Origins far apart for the rays' length (hits on different objects of a pixel block) would make
// the interval test admit every box between them: such packets take the single-ray walk.
TEST(RayPacket8, OriginsFarApartForTheirLengthAreNotCoherent) {
  Ray rays[RayPacket8::kSize];
  shadowRays(0.01f, rays);
  rays[6].origin.z += 0.3f;  // 0.03 of the length away on z; directions change by little
  rays[6].direction = glm::normalize(kLight - rays[6].origin);
  EXPECT_FALSE(RayPacket8(rays, 0xFFu).coherent);
  EXPECT_TRUE(RayPacket8(rays, 0xFFu & ~(1u << 6)).coherent);  // left out: coherent again

  // The limit follows the shortest ray: the same spread is fine for rays ten times longer.
  shadowRays(0.01f, rays);
  rays[6].origin.z += 0.3f;
  for (Ray& ray : rays) {
    const Vec3 light(0.5f, 100.0f, 0.5f);
    ray.direction = glm::normalize(light - ray.origin);
    ray.tMax = glm::length(light - ray.origin);
  }
  EXPECT_TRUE(RayPacket8(rays, 0xFFu).coherent);
}

// A dead ray (tMax below tMin, as the renderer empties a lane) is left out wherever it sits:
// its lane repeats a live ray, so its direction, origin and length do not widen the packet's
// bounds. (The first live ray once was always lane 0, dead or not: a shadow packet whose first
// lane had no ray was never coherent.)
TEST(RayPacket8, ADeadRayInAnyLaneIsLeftOut) {
  for (int dead = 0; dead < RayPacket8::kSize; ++dead) {
    Ray rays[RayPacket8::kSize];
    shadowRays(0.01f, rays);
    rays[dead] = Ray{Vec3(40.0f, -7.0f, 3.0f), Vec3(0.0f, 0.0f, 1.0f), 0.0f, -1.0f};
    const uint32_t live = 0xFFu & ~(1u << dead);
    const RayPacket8 packet(rays, live);
    EXPECT_TRUE(packet.coherent) << "dead lane " << dead;
    const int firstLive = dead == 0 ? 1 : 0;
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(packet.rayDirection[a][dead], rays[firstLive].direction[a]) << dead;
      EXPECT_EQ(packet.rayOrigin[a][dead], rays[firstLive].origin[a]) << dead;
    }
    EXPECT_LT(packet.originHigh[0], 1.0f) << dead;
  }
}

// Rays without an end (camera rays, bounces) have no limit on their origins' spread.
TEST(RayPacket8, RaysWithoutAnEndHaveNoOriginLimit) {
  Ray rays[RayPacket8::kSize];
  for (int i = 0; i < RayPacket8::kSize; ++i) {
    rays[i] = {Vec3(0.5f * static_cast<float>(i), 0.0f, 0.0f), glm::normalize(Vec3(0.1f, 1, 0.1f))};
  }
  EXPECT_TRUE(RayPacket8(rays, 0xFFu).coherent);
}

TEST(RayPacket8, SpreadOrMixedSignDirectionsAreNotCoherent) {
  Ray rays[RayPacket8::kSize];
  for (int i = 0; i < RayPacket8::kSize; ++i) {
    rays[i] = {Vec3(0.0f), glm::normalize(Vec3(0.3f + 0.01f * i, -0.5f, 0.8f))};
  }
  EXPECT_TRUE(RayPacket8(rays, 0xFFu).coherent);
  rays[3].direction = glm::normalize(Vec3(0.6f, -0.5f, 0.6f));  // 0.2 away in x
  EXPECT_FALSE(RayPacket8(rays, 0xFFu).coherent);
  rays[3].direction = glm::normalize(Vec3(-0.01f, -0.5f, 0.8f));  // x changes sign
  EXPECT_FALSE(RayPacket8(rays, 0xFFu).coherent);
}

}  // namespace
}  // namespace prism
