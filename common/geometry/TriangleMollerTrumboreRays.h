// Möller–Trumbore (geometry/TriangleMollerTrumbore.h) on one triangle and four or eight rays at
// once, the rays in the lanes: the leaf test of ray packets (accel/WideBvhPacket.h), where the
// rays of a packet share the leaf's triangles. Every lane performs the scalar test's operations
// in the scalar test's order (glm's cross and dot, no fused multiply-add), so each ray's t, u
// and v are bit for bit what the scalar test and the four-triangle test
// (TriangleMollerTrumbore4.h) give.
#pragma once

#include <cstdint>

#include "math/Simd.h"

namespace prism {

// Rays by coordinate, one per lane of V (simd::Float4 or simd::Float8).
template <class V>
struct RayLanes {
  V ox, oy, oz, dx, dy, dz, tMin;
};

// The lanes (bit i, and all ones in `inside`) whose ray hits the triangle v0, e1 = v1 - v0,
// e2 = v2 - v0 within (tMin, tMax) of that lane, with their t, u and v.
template <class V>
inline uint32_t intersectMollerTrumboreRays(const RayLanes<V>& r, const float v0[3],
                                            const float e1[3], const float e2[3], V tMax, V& tOut,
                                            V& uOut, V& vOut, simd::MaskOf<V>& inside) {
  const float e1x = e1[0], e1y = e1[1], e1z = e1[2];
  const float e2x = e2[0], e2y = e2[1], e2z = e2[2];
  // p = cross(d, e2), det = dot(e1, p)
  const V px = r.dy * e2z - e2y * r.dz;
  const V py = r.dz * e2x - e2z * r.dx;
  const V pz = r.dx * e2y - e2x * r.dy;
  const V det = e1x * px + e1y * py + e1z * pz;
  const V invDet = 1.0f / det;
  // s = origin - v0, u = dot(s, p) / det
  const V sx = r.ox - v0[0];
  const V sy = r.oy - v0[1];
  const V sz = r.oz - v0[2];
  const V u = (sx * px + sy * py + sz * pz) * invDet;
  // q = cross(s, e1), v = dot(d, q) / det, t = dot(e2, q) / det
  const V qx = sy * e1z - e1y * sz;
  const V qy = sz * e1x - e1z * sx;
  const V qz = sx * e1y - e1x * sy;
  const V v = (r.dx * qx + r.dy * qy + r.dz * qz) * invDet;
  const V t = (e2x * qx + e2y * qy + e2z * qz) * invDet;
  // The scalar test's rejections, negated as written there, so NaN lanes fare the same.
  inside = (det != 0.0f) & ~(u < 0.0f) & ~(u > 1.0f) & ~(v < 0.0f) & ~(u + v > 1.0f) &
           (t > r.tMin) & (t < tMax);
  tOut = t;
  uOut = u;
  vOut = v;
  return simd::laneMask(inside);
}

}  // namespace prism
