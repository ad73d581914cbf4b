#include "scene/Camera.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

namespace prism {
namespace {

TEST(Camera, CentreRayLooksAtTheTarget) {
  CameraDesc d;
  d.position = {1, 2, 3};
  d.lookAt = {4, 2, -1};
  const Camera camera(d, 100, 50);
  const Ray r = camera.generateRay(50.0f, 25.0f);
  const Vec3 expected = glm::normalize(d.lookAt - d.position);
  EXPECT_NEAR(glm::dot(r.direction, expected), 1.0f, 1e-6f);
  EXPECT_EQ(r.origin, d.position);
}

// A camera at the origin looking down −z with a vertical field of view of fovDegrees.
CameraDesc lookingDownMinusZ(float fovDegrees) {
  CameraDesc d;
  d.position = {0, 0, 0};
  d.lookAt = {0, 0, -1};
  d.fovDegrees = fovDegrees;
  return d;
}

TEST(Camera, VerticalFieldOfViewSpansTheImageHeight) {
  const Camera camera(lookingDownMinusZ(60.0f), 200, 100);
  const Ray top = camera.generateRay(100.0f, 0.0f);
  const Ray bottom = camera.generateRay(100.0f, 100.0f);
  EXPECT_NEAR(glm::degrees(std::acos(glm::dot(top.direction, bottom.direction))), 60.0f, 1e-3f);
  EXPECT_GT(top.direction.y, 0.0f);  // image row 0 is at the top
  const Ray right = camera.generateRay(200.0f, 50.0f);
  EXPECT_GT(right.direction.x, 0.0f);  // image x grows to the right
  // Square pixels: the horizontal half-angle is atan(aspect · tan 30°).
  EXPECT_NEAR(std::atan2(right.direction.x, -right.direction.z),
              std::atan(2.0f * std::tan(glm::radians(30.0f))), 1e-5f);
}

TEST(Camera, OrthographicRaysAreParallelAndSpanTheWidth) {
  CameraDesc d;
  d.projection = Projection::Orthographic;
  d.position = {0, 0, 5};
  d.lookAt = {0, 0, 0};
  d.width = 4.0f;
  const Camera camera(d, 40, 20);
  const Ray left = camera.generateRay(0.0f, 10.0f);
  const Ray right = camera.generateRay(40.0f, 10.0f);
  EXPECT_EQ(left.direction, right.direction);
  EXPECT_NEAR(right.origin.x - left.origin.x, 4.0f, 1e-5f);
  EXPECT_NEAR(camera.generateRay(20.0f, 0.0f).origin.y, 1.0f, 1e-5f);  // height = width / aspect
}

TEST(Camera, NearClipIsMeasuredAlongTheViewAxis) {
  CameraDesc d;
  d.position = {0, 0, 0};
  d.lookAt = {0, 0, -1};
  d.nearClip = 2.0f;
  const Camera camera(d, 10, 10);
  const Ray corner = camera.generateRay(0.0f, 0.0f);
  EXPECT_NEAR(-corner.at(corner.tMin).z, 2.0f, 1e-5f);
}

// A pixel step turns the centre ray by the pixel's angle (image plane at distance 1: 2·tan 45° /
// 100 per pixel), along the camera's right and down; the footprint on a wall 3 away is a square
// of 0.06. An orthographic pixel step moves the origin by the pixel's width instead.
TEST(Camera, APixelStepTurnsTheRayByThePixelAngleOrMovesItByThePixelWidth) {
  CameraDesc d = lookingDownMinusZ(90.0f);
  const Camera camera(d, 200, 100);
  const Ray centre = camera.generateRay(100.0f, 50.0f);
  const RayDifferential step = camera.pixelDifferential(centre);
  ASSERT_TRUE(step.valid);
  EXPECT_NEAR(glm::distance(step.dDdx, Vec3(0.02f, 0, 0)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(step.dDdy, Vec3(0, -0.02f, 0)), 0.0f, 1e-6f);
  const PixelFootprint wall = step.footprint(centre.direction, 3.0f, {0, 0, 1});
  EXPECT_NEAR(wall.area(), 0.06f * 0.06f, 1e-7f);
  // Off axis, the unit direction's change matches a finite difference of generateRay.
  const Ray corner = camera.generateRay(10.0f, 10.0f);
  const Ray nextX = camera.generateRay(10.01f, 10.0f);
  const Vec3 finite = (nextX.direction - corner.direction) / 0.01f;
  EXPECT_NEAR(glm::distance(camera.pixelDifferential(corner).dDdx, finite), 0.0f, 2e-4f);

  d.projection = Projection::Orthographic;
  d.width = 4.0f;
  const Camera orthographic(d, 40, 20);
  const RayDifferential flat = orthographic.pixelDifferential(orthographic.generateRay(3.0f, 7.0f));
  EXPECT_NEAR(glm::distance(flat.dOdx, Vec3(0.1f, 0, 0)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(flat.dOdy, Vec3(0, -0.1f, 0)), 0.0f, 1e-6f);
  EXPECT_EQ(flat.dDdx, Vec3(0.0f));
}

// A pixel block's rays are made four at a time as vector lanes (Camera::generateRays); each must
// be the ray generateRay gives alone, to the bit: perspective cameras of several shapes and
// near planes (a camera at −0 among them, whose origin keeps its sign), orthographic ones, and
// every count from 1 to 8 (the lanes and the rays left over).
TEST(Camera, RaysMadeFourAtATimeAreTheSingleRaysBitForBit) {
  std::vector<CameraDesc> cameras;
  CameraDesc tilted;
  tilted.position = {-0.0f, 3.2f, 8.5f};
  tilted.lookAt = {0.3f, 1.1f, -0.7f};
  tilted.fovDegrees = 38.0f;
  tilted.nearClip = 0.25f;
  cameras.push_back(tilted);
  cameras.push_back(lookingDownMinusZ(120.0f));
  CameraDesc orthographic = tilted;
  orthographic.projection = Projection::Orthographic;
  orthographic.width = 7.0f;
  cameras.push_back(orthographic);
  std::mt19937 random(5);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (const CameraDesc& d : cameras) {
    const Camera camera(d, 640, 360);
    for (int count = 1; count <= 8; ++count) {
      for (int trial = 0; trial < 200; ++trial) {
        float x[8], y[8];
        for (int i = 0; i < count; ++i) {
          x[i] = 640.0f * unit(random);
          y[i] = 360.0f * unit(random);
        }
        Ray rays[8];
        camera.generateRays(x, y, count, rays);
        for (int i = 0; i < count; ++i) {
          const Ray alone = camera.generateRay(x[i], y[i]);
          ASSERT_EQ(std::memcmp(&rays[i], &alone, sizeof(Ray)), 0)
              << "ray " << i << " of " << count << " at " << x[i] << ", " << y[i];
        }
      }
    }
  }
}

}  // namespace
}  // namespace prism
