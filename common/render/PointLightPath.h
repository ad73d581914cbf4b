// The path from a surface point to a point light, one point at a time: whether the light can
// reach the point, its shadow ray, and what the surface reflects of it towards the viewer
// (Phong: Lambert plus the highlight). WhittedIntegrator's direct light for lone rays;
// render/LightLanes.h does the same arithmetic for a packet's points at once.
#pragma once

#include <cmath>

#include "geometry/HitRecord.h"
#include "math/Ray.h"
#include "math/RayOffset.h"
#include "scene/SceneDescription.h"
#include "shading/LightFalloff.h"
#include "shading/Optics.h"
#include "shading/SpecularSplit.h"

namespace prism {

// What the light's contribution needs once the shadow ray is found unblocked.
struct LightPath {
  Vec3 direction{0.0f};
  float distance = 0.0f;
  float cosTheta = 0.0f;
};

// False when the light cannot reach the point (behind the surface, or at it); otherwise the
// path and its shadow ray.
inline bool towardsLight(const SurfaceHit& s, const PointLightDesc& light, LightPath& path,
                         Ray& shadow) {
  const Vec3 toLight = light.position - s.position;
  path.distance = glm::length(toLight);
  if (!(path.distance > 0.0f)) return false;
  path.direction = toLight / path.distance;
  // A light below the geometric surface cannot reach it, whatever the shading normal says.
  if (glm::dot(s.geometricNormal, path.direction) <= 0.0f) return false;
  path.cosTheta = glm::dot(s.shadingNormal, path.direction);
  if (path.cosTheta <= 0.0f) return false;
  shadow.origin = s.rayOrigin(path.direction);
  shadow.direction = path.direction;
  shadow.tMin = 0.0f;
  shadow.tMax = shadowRayLength(glm::length(light.position - shadow.origin));
  return true;
}

// What the surface (material m, diffuse albedo `albedo` at the point) sends towards the viewer
// of the light arriving along the path, per unit of the light's irradiance factor: albedo/π·cosθ
// plus the Phong highlight. Known before the shadow ray is traced: where it is exactly zero (a
// mirror or glass ball's point whose highlight is turned away, or so narrow that pow() gives 0)
// the light adds nothing, blocked or not, and no shadow ray need be traced (a sixth of the
// default scene's).
inline Color reflectance(const SurfaceHit& s, const Color& albedo, const MaterialDesc& m,
                         const LightPath& path, const Vec3& toViewer) {
  Color reflected = albedo * (kInvPi * path.cosTheta);
  if (!isBlack(m.specular)) {
    const float rv = glm::dot(reflect(-path.direction, s.shadingNormal), toViewer);
    if (rv > 0.0f) reflected += m.specular * std::pow(rv, m.shininess);
  }
  return reflected;
}

// Radiance reflected towards the viewer from an unblocked light path.
inline Color lightReflected(const PointLightDesc& light, const LightPath& path,
                            const Color& reflectance) {
  // Irradiance factor I·att(d); times albedo/π·cosθ it is Lambertian radiance in W/(m²·sr).
  const Color lightAtSurface =
      light.intensity * attenuationFactor(light.attenuation, path.distance);
  return lightAtSurface * reflectance;
}

}  // namespace prism
