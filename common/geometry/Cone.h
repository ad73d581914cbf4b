// Open truncated cone (NFF "c"): the lateral surface between a base circle and an apex circle,
// without caps; a cylinder when both radii are equal.
#pragma once

#include "geometry/MaterialId.h"
#include "math/Aabb.h"

namespace prism {

class Cone {
 public:
  Cone(const Vec3& base, float baseRadius, const Vec3& apex, float apexRadius, MaterialId material);

  Aabb bounds() const;
  // Nearest hit in (ray.tMin, tMax); the surface is two-sided.
  bool intersect(const Ray& ray, float tMax, float& tHit) const;
  // Outward normal (pointing away from the axis) at a point on the surface.
  Vec3 normalAt(const Vec3& p) const;

  MaterialId material() const { return material_; }

 private:
  Vec3 base_;
  Vec3 axis_;  // unit, base to apex
  Vec3 side1_, side2_;
  float height_;
  float baseRadius_;
  float slope_;  // radius change per unit of height
  float apexRadius_;
  MaterialId material_;
};

}  // namespace prism
