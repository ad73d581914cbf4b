// Watertight ray/triangle intersection after Woop, Benthin and Wald, "Watertight Ray/Triangle
// Intersection", Journal of Computer Graphics Techniques 2(1), 2013.
//
// The ray is made the +z axis of a sheared frame: the vertices are translated to the ray origin,
// the axes permuted so that z is the direction's largest component, and x and y sheared so the
// direction becomes (0, 0, 1). The ray then hits the triangle when the origin lies inside its 2D
// projection, which three 2D edge functions decide. Each edge function depends only on the two
// vertices of its edge, and computes exactly the negation when a neighbour lists that edge the
// other way round, so a ray through a shared edge or vertex is inside at least one of the
// triangles: no ray slips through a closed mesh. An edge function that rounds to exactly zero
// is computed again in double precision, where the products of floats are exact and the sign is
// therefore right.
//
// Deviations from the paper, and why:
// - Two-sided: the sign test accepts a triangle seen from either side, as Möller–Trumbore does
//   (refraction traces rays out of closed meshes).
// - The distance is divided out (t = T / det) and compared with (tMin, tMax) directly, instead of
//   the paper's division-free comparison, so the test reads like the other two.
// - It needs the vertices themselves, not edges computed from them: v0 + (v1 − v0) is not always
//   v1 in floating point, and watertightness rests on neighbours seeing identical vertices.
// Barycentrics follow Prism's convention p = v0 + u·(v1 − v0) + v·(v2 − v0): u weighs v1, v
// weighs v2.
#pragma once

#include <cmath>
#include <utility>

#include "math/Ray.h"

namespace prism {

// What the test needs of the ray, computed once per ray and reused for every triangle.
struct WatertightRay {
  int kx = 0, ky = 1, kz = 2;             // the permuted axes; kz is where |direction| is largest
  float sx = 0.0f, sy = 0.0f, sz = 1.0f;  // shear taking the direction to (0, 0, 1)

  WatertightRay() = default;  // the identity: for callers that use another triangle test
  explicit WatertightRay(const Vec3& direction) {
    const Vec3 a = glm::abs(direction);
    kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
    kx = kz == 2 ? 0 : kz + 1;
    ky = kx == 2 ? 0 : kx + 1;
    // Swapping x and y for a negative z keeps the triangle's winding, so the edge functions'
    // signs mean the same on both sides.
    if (direction[kz] < 0.0f) std::swap(kx, ky);
    sx = direction[kx] / direction[kz];
    sy = direction[ky] / direction[kz];
    sz = 1.0f / direction[kz];
  }
};

// Edge functions of the sheared triangle (a, b, c are the vertices' sheared x, y): u0 weighs
// vertex 0, u1 vertex 1, u2 vertex 2. Recomputed in double when one rounds to zero.
inline void watertightEdgeFunctions(float ax, float ay, float bx, float by, float cx, float cy,
                                    float& u0, float& u1, float& u2) {
  u0 = cx * by - cy * bx;
  u1 = ax * cy - ay * cx;
  u2 = bx * ay - by * ax;
  if (u0 == 0.0f || u1 == 0.0f || u2 == 0.0f) {
    u0 = static_cast<float>(double(cx) * double(by) - double(cy) * double(bx));
    u1 = static_cast<float>(double(ax) * double(cy) - double(ay) * double(cx));
    u2 = static_cast<float>(double(bx) * double(ay) - double(by) * double(ax));
  }
}

inline bool intersectWatertight(const Ray& ray, const WatertightRay& w, const Vec3& v0,
                                const Vec3& v1, const Vec3& v2, float tMax, float& tHit,
                                float& uHit, float& vHit) {
  const Vec3 a = v0 - ray.origin, b = v1 - ray.origin, c = v2 - ray.origin;
  const float ax = a[w.kx] - w.sx * a[w.kz], ay = a[w.ky] - w.sy * a[w.kz];
  const float bx = b[w.kx] - w.sx * b[w.kz], by = b[w.ky] - w.sy * b[w.kz];
  const float cx = c[w.kx] - w.sx * c[w.kz], cy = c[w.ky] - w.sy * c[w.kz];
  float u0, u1, u2;
  watertightEdgeFunctions(ax, ay, bx, by, cx, cy, u0, u1, u2);
  // Inside means all three on the same side (zero counts as either: edges are inclusive).
  if ((u0 < 0.0f || u1 < 0.0f || u2 < 0.0f) && (u0 > 0.0f || u1 > 0.0f || u2 > 0.0f)) return false;
  const float det = u0 + u1 + u2;
  if (det == 0.0f) return false;  // degenerate, or the ray lies in the triangle's plane
  const float T = u0 * (w.sz * a[w.kz]) + u1 * (w.sz * b[w.kz]) + u2 * (w.sz * c[w.kz]);
  const float invDet = 1.0f / det;
  const float t = T * invDet;
  if (!(t > ray.tMin && t < tMax)) return false;
  tHit = t;
  uHit = u1 * invDet;
  vHit = u2 * invDet;
  return true;
}

// The same with the ray's shear computed here, for callers that test one triangle per ray.
inline bool intersectWatertight(const Ray& ray, const Vec3& v0, const Vec3& v1, const Vec3& v2,
                                float tMax, float& tHit, float& uHit, float& vHit) {
  return intersectWatertight(ray, WatertightRay(ray.direction), v0, v1, v2, tMax, tHit, uHit, vHit);
}

}  // namespace prism
