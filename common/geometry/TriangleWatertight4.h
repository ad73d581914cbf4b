// The watertight test (geometry/TriangleWatertight.h) on four triangles at once. Every lane
// performs the scalar test's operations in the scalar test's order (no fused multiply-add), so
// each lane's t, u and v are bit for bit the scalar test's, and so is the closest lane it picks.
// A lane whose edge function rounds to exactly zero takes the scalar test, which recomputes the
// edge functions in double precision; that happens only for rays through an edge or a vertex.
#pragma once

#include <cstdint>

#include "geometry/TrianglePack4.h"
#include "geometry/TriangleWatertight.h"
#include "math/Simd.h"

namespace prism {

// Lanes that the ray hits within (ray.tMin, tMax), with their t, u and v.
inline uint32_t intersectWatertight4(const Ray& ray, const WatertightRay& w,
                                     const TrianglePack4& pack, float tMax, simd::Float4& tOut,
                                     simd::Float4& uOut, simd::Float4& vOut) {
  using simd::Float4;
  using simd::load;
  const Float4 ox = simd::broadcast<Float4>(ray.origin[w.kx]);
  const Float4 oy = simd::broadcast<Float4>(ray.origin[w.ky]);
  const Float4 oz = simd::broadcast<Float4>(ray.origin[w.kz]);
  const Float4 sx = simd::broadcast<Float4>(w.sx), sy = simd::broadcast<Float4>(w.sy),
               sz = simd::broadcast<Float4>(w.sz);
  // Vertices relative to the origin, in the permuted axes, then sheared.
  const Float4 az = load<Float4>(pack.v0[w.kz]) - oz;
  const Float4 bz = load<Float4>(pack.v1[w.kz]) - oz;
  const Float4 cz = load<Float4>(pack.v2[w.kz]) - oz;
  const Float4 ax = (load<Float4>(pack.v0[w.kx]) - ox) - sx * az;
  const Float4 ay = (load<Float4>(pack.v0[w.ky]) - oy) - sy * az;
  const Float4 bx = (load<Float4>(pack.v1[w.kx]) - ox) - sx * bz;
  const Float4 by = (load<Float4>(pack.v1[w.ky]) - oy) - sy * bz;
  const Float4 cx = (load<Float4>(pack.v2[w.kx]) - ox) - sx * cz;
  const Float4 cy = (load<Float4>(pack.v2[w.ky]) - oy) - sy * cz;
  const Float4 u0 = cx * by - cy * bx;
  const Float4 u1 = ax * cy - ay * cx;
  const Float4 u2 = bx * ay - by * ax;
  const Float4 det = u0 + u1 + u2;
  const Float4 T = u0 * (sz * az) + u1 * (sz * bz) + u2 * (sz * cz);
  const Float4 invDet = 1.0f / det;
  Float4 t = T * invDet;
  Float4 u = u1 * invDet;
  Float4 v = u2 * invDet;
  const auto mixedSigns =
      ((u0 < 0.0f) | (u1 < 0.0f) | (u2 < 0.0f)) & ((u0 > 0.0f) | (u1 > 0.0f) | (u2 > 0.0f));
  auto inside = ~mixedSigns & (det != 0.0f) & (t > ray.tMin) & (t < tMax);
  uint32_t mask = simd::laneMask(inside);
  // Lanes on an edge or a vertex to within rounding: the scalar test decides them exactly.
  uint32_t exact = simd::laneMask((u0 == 0.0f) | (u1 == 0.0f) | (u2 == 0.0f));
  for (; exact != 0; exact &= exact - 1) {
    const int lane = simd::firstLane(exact);
    const Vec3 p0(pack.v0[0][lane], pack.v0[1][lane], pack.v0[2][lane]);
    const Vec3 p1(pack.v1[0][lane], pack.v1[1][lane], pack.v1[2][lane]);
    const Vec3 p2(pack.v2[0][lane], pack.v2[1][lane], pack.v2[2][lane]);
    float tl, ul, vl;
    if (intersectWatertight(ray, w, p0, p1, p2, tMax, tl, ul, vl)) {
      t[lane] = tl;
      u[lane] = ul;
      v[lane] = vl;
      mask |= 1u << lane;
    } else {
      mask &= ~(1u << lane);
    }
  }
  tOut = t;
  uOut = u;
  vOut = v;
  return mask;
}

// The closest of the pack's hits (smallest t, first lane on a tie), or lane -1.
inline PackHit closestInPackWatertight(const Ray& ray, const WatertightRay& w,
                                       const TrianglePack4& pack, float tMax) {
  simd::Float4 t, u, v;
  const uint32_t mask = intersectWatertight4(ray, w, pack, tMax, t, u, v);
  return closestLane(mask, t, u, v);
}

}  // namespace prism
