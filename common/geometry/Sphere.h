// Sphere: centre and radius.
#pragma once

#include "geometry/MaterialId.h"
#include "math/Aabb.h"
#include "math/RayOffset.h"

namespace prism {

struct Sphere {
  Vec3 center{0.0f};
  float radius = 1.0f;
  MaterialId material = 0;

  Aabb bounds() const { return {center - Vec3(radius), center + Vec3(radius)}; }

  // Nearest t in (ray.tMin, tMax), for a unit-length ray direction. Uses the numerically robust
  // form of Haines et al., "Precision Improvements for Ray/Sphere Intersection" (Ray Tracing
  // Gems, 2019): the discriminant from the perpendicular distance, and the smaller root from
  // c/q, so far-away or tiny spheres do not lose their hits to cancellation.
  bool intersect(const Ray& ray, float tMax, float& tHit) const {
    const Vec3 f = ray.origin - center;
    const float b = glm::dot(f, ray.direction);
    const Vec3 perpendicular = f - b * ray.direction;
    const float discriminant = radius * radius - glm::dot(perpendicular, perpendicular);
    if (discriminant < 0.0f) return false;
    const float c = glm::dot(f, f) - radius * radius;
    const float q = -b - std::copysign(std::sqrt(discriminant), b);
    float t0 = q != 0.0f ? c / q : 0.0f;
    float t1 = q;
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > ray.tMin && t0 < tMax) {
      tHit = t0;
      return true;
    }
    if (t1 > ray.tMin && t1 < tMax) {
      tHit = t1;
      return true;
    }
    return false;
  }

  Vec3 normalAt(const Vec3& p) const { return glm::normalize(p - center); }

  // The hit point q = ray.at(t) moved onto the sphere along its radius, and the bound on that
  // point's rounding per axis: reprojected, its error no longer grows with the ray's length.
  Vec3 surfacePoint(const Vec3& q, Vec3& error) const {
    Vec3 fromCenter = q - center;
    const float length = glm::length(fromCenter);
    if (length > 0.0f) fromCenter *= radius / length;
    // Rescaling: 5 roundings (pbrt-v4, section 6.8.5); adding the centre back: one more.
    error = gamma(6) * glm::abs(fromCenter) + gamma(1) * glm::abs(center);
    return center + fromCenter;
  }
};

}  // namespace prism
