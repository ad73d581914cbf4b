// Infinite plane. Unbounded, so it lives outside the BVH and is tested for every ray.
#pragma once

#include "geometry/MaterialId.h"
#include "math/FloatError.h"
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

  // The hit point q = ray.at(t) projected onto the plane, and the bound on that point's distance
  // from it per axis: the signed distance carries 4 roundings of the terms of dot(n, q) − offset,
  // subtracting it from q one more per coordinate.
  Vec3 surfacePoint(const Vec3& q, Vec3& error) const {
    const float distance = glm::dot(normal, q) - offset;
    const Vec3 p = q - distance * normal;
    const float termSize = glm::dot(absComponents(normal), absComponents(q)) + std::fabs(offset);
    error = gammaBound(5) * absComponents(p) +
            Vec3(gammaBound(4) * termSize + gammaBound(2) * std::fabs(distance));
    return p;
  }
};

}  // namespace prism
