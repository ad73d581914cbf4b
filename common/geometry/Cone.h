// Open truncated cone (NFF "c"): the lateral surface between a base circle and an apex circle,
// without caps; a cylinder when both radii are equal. A cone may also stand for one axial
// segment of itself (segment()): the same surface, equation and arithmetic, with hits accepted
// only between two heights, so a long slanted cone can enter the BVH as several tight boxes
// (geometry/ConeSegments.h). A primitive kind of geometry/ShapeKinds.h: ConeDesc is what a scene
// file gives.
#pragma once

#include <array>
#include <optional>

#include "geometry/CausticRole.h"
#include "geometry/MaterialId.h"
#include "geometry/ShapeKeys.h"
#include "math/Aabb.h"
#include "math/Ball.h"
#include "util/FieldList.h"
#include "util/FileLoc.h"

namespace prism {

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

  MaterialId materialId() const { return material_; }
  Ball boundingBall() const { return ballAround(bounds()); }
  float height() const { return height_; }
  static constexpr bool kFlat = false;

  // The wire form of a built cone (wire/GeometryCodec.h): every member.
  PRISM_WIRE_FIELDS(base_, axis_, side1_, side2_, height_, baseRadius_, slope_, normalScale_,
                    apexRadius_, zLow_, zHigh_, material_)

 private:
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

struct ConeDesc {
  Vec3 base{0.0f};
  float baseRadius = 1.0f;
  Vec3 apex{0.0f, 1.0f, 0.0f};
  float apexRadius = 0.0f;
  MaterialId material = 0;
  FileLoc loc;
  CausticRole caustic = CausticRole::Auto;

  PRISM_WIRE_FIELDS(base, baseRadius, apex, apexRadius, material, loc, caustic)
  static constexpr std::string_view kName = "cone";
  static constexpr auto keys() {
    using Key = ShapeKey<ConeDesc>;
    return std::array{Key::point("base", &ConeDesc::base), Key::point("apex", &ConeDesc::apex),
                      Key::nonNegative("base_radius", &ConeDesc::baseRadius),
                      Key::nonNegative("apex_radius", &ConeDesc::apexRadius, false)};
  }
  // Base and apex must differ or the cone has no axis; one radius at least is above 0.
  std::optional<ShapeProblem> problem() const {
    if (base == apex) return ShapeProblem{"apex", "'apex' must differ from 'base'"};
    if (baseRadius == 0.0f && apexRadius == 0.0f) {
      return ShapeProblem{"base_radius", "a cone needs 'base_radius' or 'apex_radius' above 0"};
    }
    return std::nullopt;
  }
  Cone shape() const { return Cone(base, baseRadius, apex, apexRadius, material); }
};

}  // namespace prism
