// The closed-form caustic scene several tests share: a clear ball (radius 1, centre (0, 2, 0),
// transmittance 1, no diffuse, index `ior`) over a Lambertian floor y = 0 of albedo
// kBallFloorAlbedo, under a point light of kBallLightIntensity W/sr at (0, kBallLightHeight, 0)
// with inverse-square falloff. With ior = 1 (Fresnel reflects nothing) the light passes the ball
// undeviated, so the floor in its shadow must receive exactly the direct irradiance
// E = I·h/d³ — but only through caustics, since shadow rays stop at the ball.
#pragma once

#include <cmath>

#include "scene/SceneDescription.h"

namespace prism::test {

inline constexpr float kBallLightIntensity = 100.0f;
inline constexpr float kBallLightHeight = 4.0f;
inline constexpr float kBallFloorAlbedo = 0.8f;

inline SceneDescription ballOverFloorScene(float ior) {
  SceneDescription d;
  MaterialDesc ball;
  ball.diffuse = Color(0.0f);
  ball.transmittance = Color(1.0f);
  ball.ior = ior;
  MaterialDesc floor;
  floor.diffuse = Color(kBallFloorAlbedo);
  d.materials = {ball, floor};
  d.spheres.push_back({{0, 2, 0}, 1.0f, 0, {}});
  d.planes.push_back({{0, 0, 0}, {0, 1, 0}, 1, {}});
  PointLightDesc light;
  light.position = {0, kBallLightHeight, 0};
  light.intensity = Color(kBallLightIntensity);
  d.lights.push_back(light);
  return d;
}

// I·h/d³ at floor point (x, 0, z).
inline double ballOverFloorDirectIrradiance(double x, double z) {
  const double d2 = kBallLightHeight * kBallLightHeight + x * x + z * z;
  return kBallLightIntensity * kBallLightHeight / (d2 * std::sqrt(d2));
}

}  // namespace prism::test
