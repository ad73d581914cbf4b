// Möller–Trumbore (geometry/TriangleMollerTrumbore.h) on four triangles at once, stored as a
// structure of arrays (geometry/TrianglePack4.h). Every lane performs the scalar test's
// operations in the scalar test's order (the edges v1 − v0 and v2 − v0, glm's cross and dot, no
// fused multiply-add), so each lane's t, u and v are bit for bit what the scalar test computes,
// and so is the hit it picks: the smallest t, the first lane on a tie, exactly as testing the
// four one after another with a shrinking tMax would.
#pragma once

#include <cstdint>

#include "geometry/TrianglePack4.h"
#include "math/Ray.h"
#include "math/Simd.h"

namespace prism {

// Lanes that the ray hits within (ray.tMin, tMax), with their t, u and v.
inline uint32_t intersectMollerTrumbore4(const Ray& ray, const TrianglePack4& pack, float tMax,
                                         simd::Float4& tOut, simd::Float4& uOut,
                                         simd::Float4& vOut) {
  using simd::Float4;
  using simd::load;
  const Float4 dx = simd::broadcast<Float4>(ray.direction.x);
  const Float4 dy = simd::broadcast<Float4>(ray.direction.y);
  const Float4 dz = simd::broadcast<Float4>(ray.direction.z);
  const Float4 v0x = load<Float4>(pack.v0[0]), v0y = load<Float4>(pack.v0[1]),
               v0z = load<Float4>(pack.v0[2]);
  const Float4 e1x = load<Float4>(pack.v1[0]) - v0x, e1y = load<Float4>(pack.v1[1]) - v0y,
               e1z = load<Float4>(pack.v1[2]) - v0z;
  const Float4 e2x = load<Float4>(pack.v2[0]) - v0x, e2y = load<Float4>(pack.v2[1]) - v0y,
               e2z = load<Float4>(pack.v2[2]) - v0z;
  // p = cross(d, e2), det = dot(e1, p)
  const Float4 px = dy * e2z - e2y * dz;
  const Float4 py = dz * e2x - e2z * dx;
  const Float4 pz = dx * e2y - e2x * dy;
  const Float4 det = e1x * px + e1y * py + e1z * pz;
  const Float4 invDet = 1.0f / det;
  // s = origin - v0, u = dot(s, p) / det
  const Float4 sx = simd::broadcast<Float4>(ray.origin.x) - v0x;
  const Float4 sy = simd::broadcast<Float4>(ray.origin.y) - v0y;
  const Float4 sz = simd::broadcast<Float4>(ray.origin.z) - v0z;
  const Float4 u = (sx * px + sy * py + sz * pz) * invDet;
  // q = cross(s, e1), v = dot(d, q) / det, t = dot(e2, q) / det
  const Float4 qx = sy * e1z - e1y * sz;
  const Float4 qy = sz * e1x - e1z * sx;
  const Float4 qz = sx * e1y - e1x * sy;
  const Float4 v = (dx * qx + dy * qy + dz * qz) * invDet;
  const Float4 t = (e2x * qx + e2y * qy + e2z * qz) * invDet;
  // The scalar test's rejections, negated as written there, so NaN lanes fare the same.
  const auto inside = (det != 0.0f) & ~(u < 0.0f) & ~(u > 1.0f) & ~(v < 0.0f) & ~(u + v > 1.0f) &
                      (t > ray.tMin) & (t < tMax);
  tOut = t;
  uOut = u;
  vOut = v;
  return simd::laneMask(inside);
}

// The closest of the pack's hits (smallest t, first lane on a tie), or lane -1.
inline PackHit closestInPack(const Ray& ray, const TrianglePack4& pack, float tMax) {
  simd::Float4 t, u, v;
  const uint32_t mask = intersectMollerTrumbore4(ray, pack, tMax, t, u, v);
  return closestLane(mask, t, u, v);
}

}  // namespace prism
