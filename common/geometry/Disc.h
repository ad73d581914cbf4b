// Disc: a flat circle of given centre, normal and radius, seen from both sides (a lid, a
// coin, a round mirror). A primitive kind of geometry/ShapeKinds.h: DiscDesc is what a scene
// file gives. The hit is the plane's (geometry/Plane.h, the same arithmetic), kept when it lies
// within the radius.
#pragma once

#include <array>
#include <optional>

#include "geometry/CausticRole.h"
#include "geometry/MaterialId.h"
#include "geometry/ShapeKeys.h"
#include "math/Aabb.h"
#include "math/Ball.h"
#include "math/FloatError.h"
#include "math/Ray.h"
#include "util/FieldList.h"
#include "util/FileLoc.h"

namespace prism {

struct Disc {
  Vec3 center{0.0f};
  Vec3 normal{0.0f, 1.0f, 0.0f};  // unit
  float radius = 1.0f;
  float offset = 0.0f;  // dot(normal, x) == offset on the disc's plane
  MaterialId material = 0;

  PRISM_WIRE_FIELDS(center, normal, radius, offset, material)
  static constexpr bool kMemoryIsWireForm = true;  // nine packed fields of four bytes
  static constexpr bool kFlat = true;  // a pixel's footprint goes on unturned, as on a plane

  MaterialId materialId() const { return material; }
  Ball boundingBall() const { return {center, radius}; }

  // The circle bounds each axis by radius · sqrt(1 − normal_i²), widened by the rounding of the
  // hit points the radius test accepts.
  Aabb bounds() const {
    const Vec3 spread = glm::sqrt(glm::max(Vec3(0.0f), Vec3(1.0f) - normal * normal));
    const Vec3 reach = radius * spread + gammaBound(4) * (absComponents(center) + Vec3(radius));
    return {center - reach, center + reach};
  }

  // Nearest t in (ray.tMin, tMax); a grazing ray (parallel to the disc) never meets it.
  bool intersect(const Ray& ray, float tMax, float& tHit) const {
    const float denominator = glm::dot(normal, ray.direction);
    if (denominator == 0.0f) return false;
    const float t = (offset - glm::dot(normal, ray.origin)) / denominator;
    if (!(t > ray.tMin && t < tMax)) return false;
    const Vec3 fromCenter = ray.at(t) - center;
    if (glm::dot(fromCenter, fromCenter) > radius * radius) return false;
    tHit = t;
    return true;
  }

  // The hit q projected onto the disc's plane with Plane::surfacePoint's rounding bound, and
  // the normal.
  Vec3 surfacePoint(const Vec3& q, Vec3& error, Vec3& outNormal) const {
    const float distance = glm::dot(normal, q) - offset;
    const Vec3 p = q - distance * normal;
    const float termSize = glm::dot(absComponents(normal), absComponents(q)) + std::fabs(offset);
    error = gammaBound(5) * absComponents(p) +
            Vec3(gammaBound(4) * termSize + gammaBound(2) * std::fabs(distance));
    outNormal = normal;
    return p;
  }
};
static_assert(sizeof(Disc) == 36);

struct DiscDesc {
  Vec3 center{0.0f};
  Vec3 normal{0.0f, 1.0f, 0.0f};  // unit length after parsing
  float radius = 1.0f;
  MaterialId material = 0;
  FileLoc loc;
  CausticRole caustic = CausticRole::Auto;

  PRISM_WIRE_FIELDS(center, normal, radius, material, loc, caustic)
  static constexpr std::string_view kName = "disc";
  static constexpr auto keys() {
    using Key = ShapeKey<DiscDesc>;
    return std::array{Key::point("center", &DiscDesc::center),
                      Key::direction("normal", &DiscDesc::normal),
                      Key::positive("radius", &DiscDesc::radius)};
  }
  std::optional<ShapeProblem> problem() const { return std::nullopt; }
  Disc shape() const {
    const Vec3 n = glm::normalize(normal);
    return {center, n, radius, glm::dot(n, center), material};
  }
};

}  // namespace prism
