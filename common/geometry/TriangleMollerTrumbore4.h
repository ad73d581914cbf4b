// Möller–Trumbore (geometry/TriangleMollerTrumbore.h) on four triangles at once, stored as a
// structure of arrays. Every lane performs the scalar test's operations in the scalar test's
// order (glm's cross and dot, no fused multiply-add), so each lane's t, u and v are bit for bit
// what the scalar test computes, and so is the hit it picks: the smallest t, the first lane on a
// tie, exactly as testing the four one after another with a shrinking tMax would.
#pragma once

#include <cstdint>

#include "accel/Simd.h"
#include "geometry/Triangle.h"
#include "math/Ray.h"

namespace prism {

struct alignas(16) TrianglePack4 {
  static constexpr int kWidth = 4;
  // v0, e1, e2 by coordinate. Unused lanes are all zero: det == 0 rejects them.
  float v0[3][kWidth] = {};
  float e1[3][kWidth] = {};
  float e2[3][kWidth] = {};
  uint32_t triangle[kWidth] = {};  // index of each lane's triangle in the scene's array

  void set(int lane, const Triangle& tri, uint32_t index) {
    for (int a = 0; a < 3; ++a) {
      v0[a][lane] = tri.v0[a];
      e1[a][lane] = tri.e1[a];
      e2[a][lane] = tri.e2[a];
    }
    triangle[lane] = index;
  }
};

struct PackHit {
  int lane = -1;
  float t = 0.0f, u = 0.0f, v = 0.0f;
};

// Lanes that the ray hits within (ray.tMin, tMax), with their t, u and v.
inline uint32_t intersectMollerTrumbore4(const Ray& ray, const TrianglePack4& pack, float tMax,
                                         simd::Float4& tOut, simd::Float4& uOut,
                                         simd::Float4& vOut) {
  using simd::Float4;
  using simd::load;
  const Float4 dx = simd::broadcast<Float4>(ray.direction.x);
  const Float4 dy = simd::broadcast<Float4>(ray.direction.y);
  const Float4 dz = simd::broadcast<Float4>(ray.direction.z);
  const Float4 e1x = load<Float4>(pack.e1[0]), e1y = load<Float4>(pack.e1[1]),
               e1z = load<Float4>(pack.e1[2]);
  const Float4 e2x = load<Float4>(pack.e2[0]), e2y = load<Float4>(pack.e2[1]),
               e2z = load<Float4>(pack.e2[2]);
  // p = cross(d, e2), det = dot(e1, p)
  const Float4 px = dy * e2z - e2y * dz;
  const Float4 py = dz * e2x - e2z * dx;
  const Float4 pz = dx * e2y - e2x * dy;
  const Float4 det = e1x * px + e1y * py + e1z * pz;
  const Float4 invDet = 1.0f / det;
  // s = origin - v0, u = dot(s, p) / det
  const Float4 sx = simd::broadcast<Float4>(ray.origin.x) - load<Float4>(pack.v0[0]);
  const Float4 sy = simd::broadcast<Float4>(ray.origin.y) - load<Float4>(pack.v0[1]);
  const Float4 sz = simd::broadcast<Float4>(ray.origin.z) - load<Float4>(pack.v0[2]);
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
  uint32_t mask = intersectMollerTrumbore4(ray, pack, tMax, t, u, v);
  PackHit best;
  while (mask != 0) {
    const int lane = simd::firstLane(mask);
    mask &= mask - 1;
    if (best.lane < 0 || t[lane] < best.t) best = {lane, t[lane], u[lane], v[lane]};
  }
  return best;
}

}  // namespace prism
