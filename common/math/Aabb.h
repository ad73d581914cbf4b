// Axis-aligned bounding box, used by the BVH builder and traversal.
#pragma once

#include <limits>

#include "math/Ray.h"

namespace prism {

struct Aabb {
  Vec3 lower{std::numeric_limits<float>::infinity()};
  Vec3 upper{-std::numeric_limits<float>::infinity()};

  bool empty() const { return lower.x > upper.x || lower.y > upper.y || lower.z > upper.z; }
  // Whether p lies in the box, its faces included (never for a NaN coordinate).
  bool contains(const Vec3& p) const {
    return p.x >= lower.x && p.y >= lower.y && p.z >= lower.z && p.x <= upper.x && p.y <= upper.y &&
           p.z <= upper.z;
  }
  void extend(const Vec3& p) {
    lower = glm::min(lower, p);
    upper = glm::max(upper, p);
  }
  void extend(const Aabb& b) {
    lower = glm::min(lower, b.lower);
    upper = glm::max(upper, b.upper);
  }
  Vec3 center() const { return 0.5f * (lower + upper); }
  Vec3 extent() const { return upper - lower; }
  float surfaceArea() const {
    if (empty()) return 0.0f;
    const Vec3 e = extent();
    return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
  }
  int longestAxis() const {
    const Vec3 e = extent();
    return (e.x >= e.y && e.x >= e.z) ? 0 : (e.y >= e.z ? 1 : 2);
  }
};

}  // namespace prism
