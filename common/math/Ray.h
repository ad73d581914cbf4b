// A ray with its valid parameter interval [tMin, tMax].
#pragma once

#include <limits>

#include "math/Vec.h"

namespace prism {

struct Ray {
  Vec3 origin{0.0f};
  Vec3 direction{0.0f, 0.0f, 1.0f};  // not necessarily unit length for every caller; see users
  float tMin = 0.0f;
  float tMax = std::numeric_limits<float>::infinity();

  Vec3 at(float t) const { return origin + t * direction; }
};

// Offsets a surface point along its geometric normal so a ray leaving it does not hit the same
// surface again. The offset grows with the coordinates' magnitude because float spacing does.
inline Vec3 offsetRayOrigin(const Vec3& p, const Vec3& geometricNormal, const Vec3& direction) {
  constexpr float kRelative = 2e-5f;
  constexpr float kAbsolute = 1e-5f;
  const float eps = kAbsolute + kRelative * maxAbsComponent(p);
  const Vec3 n = glm::dot(geometricNormal, direction) < 0.0f ? -geometricNormal : geometricNormal;
  return p + eps * n;
}

}  // namespace prism
