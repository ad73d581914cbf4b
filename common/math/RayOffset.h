// Where a ray leaving a surface starts: just outside the rounding error of the computed hit
// point, so it can neither hit the surface it leaves (shadow acne) nor start beyond a nearby
// surface (light leaks). The error bounds come from each primitive's own arithmetic
// (Scene::surface); the method is pbrt-v4's (Pharr, Jakob & Humphreys, "Physically Based
// Rendering", 4th ed., section 6.8), with γ(n) = gammaBound(n) (math/FloatError.h).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "math/FloatError.h"
#include "math/Vec.h"

namespace prism {

// How far a ray leaving surface point p (each coordinate within positionError of the true
// point) must start from it along the surface's unit geometric normal n: beyond the error box
// around p (pbrt-v4, section 6.8.6). Where pbrt then steps each coordinate one float further, the
// distance here also covers the rounding of the move itself (computing it, scaling n, adding to
// p: γ(8) of it, and one rounding of p's coordinates along n): a few multiplies instead of three
// bit-steps with branches. Never less than the smallest normal float: an exact point still moves
// off its surface, and an origin never becomes subnormal (a microcode assist in every later test
// of the ray). It does not depend on the ray: SurfaceHit keeps it for all rays leaving a hit.
inline float leavingDistance(const Vec3& p, const Vec3& positionError, const Vec3& n) {
  const Vec3 absN = absComponents(n);
  const float reach = (1.0f + gammaBound(8)) * glm::dot(absN, positionError) +
                      gammaBound(3) * glm::dot(absN, absComponents(p));
  return std::max(reach, std::numeric_limits<float>::min());
}

// The part of a hit's position error that comes from its distance t along the ray that found it,
// per axis. Two surfaces whose computed distances lie within the rounding of t cannot be ordered:
// the one taken as nearer may lie that far behind the other, and its point (put back on its own
// surface, so its own error is small) then lies inside the other surface. Where overlapping
// spheres meet (SPD's shells) rays leaving such points hit the other sphere at once: black
// pixels. Measured on shells-s5 at 512x512 (eye 70 units away): 66 shadow rays blocked within
// 10⁻³ of their origin with no allowance, 1 with γ(4)·t, none with γ(8)·t; on a row of spheres
// (LeavingSurfaces.OverlappingSpheres...) up to 1430 of 3400 lit points dark, 2 of 12 cases dark
// with γ(4), none with γ(8). γ(16) keeps a factor of two. It grows with the ray's length, as the
// ordering's uncertainty does: about 10⁻⁶ of it, below what the incoming ray can resolve.
inline Vec3 hitDistanceError(float t, const Vec3& direction) {
  return gammaBound(16) * t * absComponents(direction);
}

// The origin for a ray leaving p in direction w: `distance` along n, to the side w goes.
inline Vec3 leavingOrigin(const Vec3& p, const Vec3& n, float distance, const Vec3& w) {
  return p + (glm::dot(w, n) < 0.0f ? -distance : distance) * n;
}

// The length of a shadow ray to a point light at `distance` (computed in float): it stops short
// of the light by more than the rounding of that distance and of an occluder's t, so a light set
// into a surface (a bulb in a ceiling, an NFF light on a wall) is not shadowed by that surface.
// Measured (LeavingSurfaces.ALightSetIntoASurface...): stopping γ(4) short still left up to 5 of
// 2000 floor points dark, γ(8) none; γ(16) keeps a factor of two.
// A template so that vectors of distances (render/LightLanes.h) take the same multiplication.
template <class Distance>
inline Distance shadowRayLength(Distance distance) {
  return distance * (1.0f - gammaBound(16));
}

}  // namespace prism
