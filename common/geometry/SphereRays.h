// The sphere test (geometry/Sphere.h) on one sphere and four or eight rays at once, the rays in
// the lanes: the leaf test of ray packets (accel/WideBvhPacket.h) for leaves of spheres. Every
// lane performs the scalar test's operations in its order (glm's dot, correctly rounded square
// root and division, no fused multiply-add), so each ray's t is bit for bit the scalar one.
#pragma once

#include <cstdint>

#include "geometry/Sphere.h"
#include "geometry/TriangleMollerTrumboreRays.h"
#include "math/Simd.h"

namespace prism {

// The lanes (bit i, and all ones in `inside`) whose ray hits the sphere within (tMin, tMax) of
// that lane, with their t: the nearer root where it lies in the interval, else the farther.
template <class V>
inline uint32_t intersectSphereRays(const RayLanes<V>& r, const Sphere& sphere, V tMax, V& tOut,
                                    simd::MaskOf<V>& inside) {
  const float radius2 = sphere.radius * sphere.radius;
  // f = origin - center, b = dot(f, d), perpendicular = f - b·d
  const V fx = r.ox - sphere.center.x;
  const V fy = r.oy - sphere.center.y;
  const V fz = r.oz - sphere.center.z;
  const V b = fx * r.dx + fy * r.dy + fz * r.dz;
  const V px = fx - b * r.dx;
  const V py = fy - b * r.dy;
  const V pz = fz - b * r.dz;
  const V discriminant = radius2 - (px * px + py * py + pz * pz);
  const simd::MaskOf<V> crosses = ~(discriminant < 0.0f);
  const V c = (fx * fx + fy * fy + fz * fz) - radius2;
  // Lanes that miss take the root of a negative number; their NaNs are masked off below.
  const V q = -b - simd::copySign(simd::sqrtLanes(discriminant), b);
  const V t0 = simd::select<V>(q != 0.0f, c / q, V{});
  const V t1 = q;
  const simd::MaskOf<V> swap = t0 > t1;
  const V nearer = simd::select<V>(swap, t1, t0);
  const V farther = simd::select<V>(swap, t0, t1);
  const simd::MaskOf<V> nearIn = (nearer > r.tMin) & (nearer < tMax);
  const simd::MaskOf<V> farIn = (farther > r.tMin) & (farther < tMax);
  inside = crosses & (nearIn | farIn);
  tOut = simd::select<V>(nearIn, nearer, farther);
  return simd::laneMask(inside);
}

}  // namespace prism
