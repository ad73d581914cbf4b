// Infinite plane. Unbounded, so it lives outside the BVH and is tested for every ray.
#pragma once

#include "geometry/MaterialId.h"
#include "math/Ray.h"

namespace prism {

struct Plane {
  Vec3 normal{0.0f, 1.0f, 0.0f};  // unit
  float offset = 0.0f;            // dot(normal, x) == offset on the plane
  MaterialId material = 0;

  bool intersect(const Ray& ray, float tMax, float& tHit) const {
    const float denominator = glm::dot(normal, ray.direction);
    if (denominator == 0.0f) return false;  // parallel: a grazing ray never meets it
    const float t = (offset - glm::dot(normal, ray.origin)) / denominator;
    if (!(t > ray.tMin && t < tMax)) return false;
    tHit = t;
    return true;
  }
};

}  // namespace prism
