// Open truncated cone (NFF "c"): the lateral surface between a base circle and an apex circle,
// without caps; a cylinder when both radii are equal. A cone may also stand for one axial
// segment of itself (segment()): the same surface, equation and arithmetic, with hits accepted
// only between two heights, so a long slanted cone can enter the BVH as several tight boxes.
#pragma once

#include "geometry/MaterialId.h"
#include "math/Aabb.h"

namespace prism {
namespace wire {
template <class T>
struct Fields;
}

class Cone {
 public:
  Cone() = default;  // a degenerate cone nothing hits, for a reader of the wire form to fill
  Cone(const Vec3& base, float baseRadius, const Vec3& apex, float apexRadius, MaterialId material);

  // The part of this cone between heights zLow and zHigh along the axis (0 ≤ zLow < zHigh ≤
  // height()). A hit in it has the very t the whole cone computes for that hit.
  Cone segment(float zLow, float zHigh) const;

  // Bounds of the segment's lateral surface (of the whole cone unless segment() made it).
  Aabb bounds() const;
  // Nearest hit in (ray.tMin, tMax) within the segment; the surface is two-sided.
  bool intersect(const Ray& ray, float tMax, float& tHit) const;
  // Outward normal (pointing away from the axis) at a point on the surface.
  Vec3 normalAt(const Vec3& p) const;
  // The hit point q = ray.at(t) moved onto the surface across the axis, the bound on that
  // point's rounding per axis (independent of the ray's length, as for the sphere), and the
  // outward normal there (normalAt's, from the same radial direction).
  Vec3 surfacePoint(const Vec3& q, Vec3& error, Vec3& normal) const;

  MaterialId material() const { return material_; }
  float height() const { return height_; }

 private:
  template <class T>
  friend struct wire::Fields;  // the wire form lists the members (wire/GeometryCodec.h)

  Vec3 base_{0.0f};
  Vec3 axis_{0.0f, 0.0f, 1.0f};  // unit, base to apex
  Vec3 side1_{1.0f, 0.0f, 0.0f}, side2_{0.0f, 1.0f, 0.0f};
  float height_ = 0.0f;
  float baseRadius_ = 0.0f;
  float slope_ = 0.0f;        // radius change per unit of height
  float normalScale_ = 1.0f;  // 1 / sqrt(1 + slope²): normalises (radial unit − slope · axis)
  float apexRadius_ = 0.0f;
  // The segment this cone stands for: hits with zLow_ ≤ z ≤ zHigh_ (the whole cone: 0, height_).
  float zLow_ = 0.0f, zHigh_ = 0.0f;
  MaterialId material_ = 0;
};

}  // namespace prism
