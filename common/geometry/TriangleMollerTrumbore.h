// Ray/triangle intersection after Möller and Trumbore, "Fast, Minimum Storage Ray/Triangle
// Intersection", Journal of Graphics Tools 2(1), 1997.
//
// Deviations from the paper, and why:
// - No culling: both faces are hit, because refraction traces rays out of closed meshes.
// - Epsilon: the paper rejects |det| < 1e-6. The determinant scales with |e1|·|e2|·|d|, so an
//   absolute threshold silently drops small triangles in small scenes. We reject only det == 0;
//   near-parallel rays give a huge 1/det whose u or v then fails the range test.
// - Edges are inclusive (u ≥ 0, v ≥ 0, u + v ≤ 1). Floating-point rounding still lets a ray
//   through a shared edge miss both triangles: the method is not watertight. The crack rate is
//   measured by tests/common/geometry/TriangleMollerTrumbore_test.cpp and docs/stability.md.
// The edges e1 = v1 − v0, e2 = v2 − v0 are precomputed once per triangle.
#pragma once

#include "math/Ray.h"

namespace prism {

inline bool intersectMollerTrumbore(const Ray& ray, const Vec3& v0, const Vec3& e1, const Vec3& e2,
                                    float tMax, float& tHit, float& uHit, float& vHit) {
  const Vec3 p = glm::cross(ray.direction, e2);
  const float det = glm::dot(e1, p);
  if (det == 0.0f) return false;
  const float invDet = 1.0f / det;
  const Vec3 s = ray.origin - v0;
  const float u = glm::dot(s, p) * invDet;
  if (u < 0.0f || u > 1.0f) return false;
  const Vec3 q = glm::cross(s, e1);
  const float v = glm::dot(ray.direction, q) * invDet;
  if (v < 0.0f || u + v > 1.0f) return false;
  const float t = glm::dot(e2, q) * invDet;
  if (!(t > ray.tMin && t < tMax)) return false;
  tHit = t;
  uHit = u;
  vHit = v;
  return true;
}

}  // namespace prism
