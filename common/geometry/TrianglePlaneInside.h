// The classic two-step ray/triangle test, kept beside Möller–Trumbore for comparison (selected
// with render.triangle_test: plane-inside): intersect the triangle's supporting plane, then test
// whether the hit point lies inside using the signs of the sub-triangle areas (e.g. Glassner,
// "An Introduction to Ray Tracing", 1989, ch. 2). It needs the normal, which it recomputes from
// the precomputed edges so both tests read the same triangle data. Two-sided, inclusive edges,
// and only an exactly parallel ray (dot(n, d) == 0) is rejected, as for Möller–Trumbore.
#pragma once

#include "math/Ray.h"

namespace prism {

inline bool intersectPlaneThenInside(const Ray& ray, const Vec3& v0, const Vec3& e1, const Vec3& e2,
                                     float tMax, float& tHit, float& uHit, float& vHit) {
  const Vec3 n = glm::cross(e1, e2);
  const float denominator = glm::dot(n, ray.direction);
  if (denominator == 0.0f) return false;
  const float t = glm::dot(n, v0 - ray.origin) / denominator;
  if (!(t > ray.tMin && t < tMax)) return false;
  // Barycentrics of the plane hit from signed areas: p − v0 = u·e1 + v·e2.
  const Vec3 rel = ray.at(t) - v0;
  const float invArea2 = 1.0f / glm::dot(n, n);
  const float u = glm::dot(glm::cross(rel, e2), n) * invArea2;
  if (u < 0.0f || u > 1.0f) return false;
  const float v = glm::dot(glm::cross(e1, rel), n) * invArea2;
  if (v < 0.0f || u + v > 1.0f) return false;
  tHit = t;
  uHit = u;
  vHit = v;
  return true;
}

}  // namespace prism
