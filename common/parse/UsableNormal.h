// Which vertex normals a mesh reader may keep.
#pragma once

#include <cmath>

#include "math/Vec.h"

namespace prism {

// Whether normalising n gives a unit vector: not zero (exporters write zero normals for
// degenerate faces), and not so small or so large that its length under- or overflows (a
// normal of 1e-30 in every component normalises to NaN, one of 1e30 to zero).
inline bool isUsableNormal(const Vec3& n) {
  if (!isFinite(n) || maxAbsComponent(n) == 0.0f) return false;
  const Vec3 unit = glm::normalize(n);
  return isFinite(unit) && std::abs(glm::length(unit) - 1.0f) < 1e-3f;
}

}  // namespace prism
