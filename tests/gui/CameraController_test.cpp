#include "gui/CameraController.h"

#include <gtest/gtest.h>

namespace prism {
namespace {

CameraDesc home() {
  CameraDesc c;
  c.position = Vec3(0.0f, 0.0f, 10.0f);
  c.lookAt = Vec3(0.0f, 0.0f, 0.0f);
  c.up = Vec3(0.0f, 1.0f, 0.0f);
  return c;
}

void expectNear(const Vec3& a, const Vec3& b) {
  EXPECT_NEAR(a.x, b.x, 1e-5f);
  EXPECT_NEAR(a.y, b.y, 1e-5f);
  EXPECT_NEAR(a.z, b.z, 1e-5f);
}

TEST(CameraController, MovesInStepsOfAFractionOfTheDistance) {
  CameraController c(home());
  c.move(1, 0, 0);  // forward is -z; step 0.05 x 10
  expectNear(c.camera().position, Vec3(0.0f, 0.0f, 9.5f));
  expectNear(c.camera().lookAt, Vec3(0.0f, 0.0f, -0.5f));
  c.move(0, 1, 0);  // right is +x
  expectNear(c.camera().position, Vec3(0.5f, 0.0f, 9.5f));
  c.move(0, 0, -1);  // down
  expectNear(c.camera().position, Vec3(0.5f, -0.5f, 9.5f));
  c.reset();
  expectNear(c.camera().position, home().position);
}

TEST(CameraController, RotateTurnsInPlaceOrbitKeepsTheDistance) {
  CameraController c(home());
  c.rotate(90.0f, 0.0f);  // yaw left: looks along -x
  expectNear(c.camera().position, home().position);
  expectNear(c.camera().lookAt, Vec3(-10.0f, 0.0f, 10.0f));
  c.reset();
  c.orbit(90.0f, 0.0f);
  expectNear(c.camera().lookAt, Vec3(0.0f));
  expectNear(c.camera().position, Vec3(10.0f, 0.0f, 0.0f));
  c.orbit(0.0f, 89.9f);  // too close to the up vector: refused
  expectNear(c.camera().position, Vec3(10.0f, 0.0f, 0.0f));
}

TEST(CameraController, ZoomScalesTheDistanceAndStopsShortOfTheTarget) {
  CameraController c(home());
  c.zoom(0.5f);
  EXPECT_NEAR(c.distance(), 5.0f, 1e-5f);
  for (int i = 0; i < 200; ++i) c.zoom(0.5f);
  EXPECT_NEAR(c.distance(), 0.01f, 1e-6f);
}

}  // namespace
}  // namespace prism
