// Sphere: centre and radius. A primitive kind of geometry/ShapeKinds.h: the description a scene
// file gives (SphereDesc) and the sphere the walks test.
#pragma once

#include <array>
#include <optional>

#include "geometry/CausticRole.h"
#include "geometry/MaterialId.h"
#include "geometry/ShapeKeys.h"
#include "math/Aabb.h"
#include "math/Ball.h"
#include "math/FloatError.h"
#include "util/FieldList.h"
#include "util/FileLoc.h"

namespace prism {

struct Sphere {
  Vec3 center{0.0f};
  float radius = 1.0f;
  MaterialId material = 0;

  PRISM_WIRE_FIELDS(center, radius, material)
  static constexpr bool kMemoryIsWireForm = true;  // three packed fields of four bytes
  static constexpr bool kFlat = false;

  MaterialId materialId() const { return material; }
  Ball boundingBall() const { return {center, radius}; }

  Aabb bounds() const { return {center - Vec3(radius), center + Vec3(radius)}; }

  // Nearest t in (ray.tMin, tMax), for a unit-length ray direction. Uses the numerically robust
  // form of Haines et al., "Precision Improvements for Ray/Sphere Intersection" (Ray Tracing
  // Gems, 2019): the discriminant from the perpendicular distance, and the smaller root from
  // c/q, so far-away or tiny spheres do not lose their hits to cancellation.
  bool intersect(const Ray& ray, float tMax, float& tHit) const {
    const Vec3 f = ray.origin - center;
    const float b = glm::dot(f, ray.direction);
    const Vec3 perpendicular = f - b * ray.direction;
    const float discriminant = radius * radius - glm::dot(perpendicular, perpendicular);
    if (discriminant < 0.0f) return false;
    const float c = glm::dot(f, f) - radius * radius;
    const float q = -b - std::copysign(std::sqrt(discriminant), b);
    float t0 = q != 0.0f ? c / q : 0.0f;
    float t1 = q;
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > ray.tMin && t0 < tMax) {
      tHit = t0;
      return true;
    }
    if (t1 > ray.tMin && t1 < tMax) {
      tHit = t1;
      return true;
    }
    return false;
  }

  Vec3 normalAt(const Vec3& p) const { return glm::normalize(p - center); }

  // The surface point in the direction of unit normal n from the centre (the hit q = ray.at(t)
  // reprojected, with n = normalAt(q)), and the bound on its rounding per axis: n carries about
  // 5 roundings, scaling by the radius and adding the centre one each. Unlike q's, this error
  // does not grow with the ray's length.
  Vec3 pointAlong(const Vec3& n, Vec3& error) const {
    const Vec3 fromCenter = radius * n;
    error = gammaBound(7) * absComponents(fromCenter) + gammaBound(1) * absComponents(center);
    return center + fromCenter;
  }
  // The hit q put back on the sphere (pointAlong), its rounding bound and the outward normal.
  Vec3 surfacePoint(const Vec3& q, Vec3& error, Vec3& normal) const {
    normal = normalAt(q);
    return pointAlong(normal, error);
  }
};
static_assert(sizeof(Sphere) == 20);

struct SphereDesc {
  Vec3 center{0.0f};
  float radius = 1.0f;
  MaterialId material = 0;
  FileLoc loc;
  CausticRole caustic = CausticRole::Auto;

  PRISM_WIRE_FIELDS(center, radius, material, loc, caustic)
  static constexpr std::string_view kName = "sphere";
  static constexpr auto keys() {
    using Key = ShapeKey<SphereDesc>;
    return std::array{Key::point("center", &SphereDesc::center),
                      Key::positive("radius", &SphereDesc::radius)};
  }
  std::optional<ShapeProblem> problem() const { return std::nullopt; }
  Sphere shape() const { return {center, radius, material}; }
};

}  // namespace prism
