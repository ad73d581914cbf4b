#include "geometry/Cone.h"

#include <algorithm>

#include "math/FloatError.h"

namespace prism {

Cone::Cone(const Vec3& base, float baseRadius, const Vec3& apex, float apexRadius,
           MaterialId material)
    : base_(base), baseRadius_(baseRadius), apexRadius_(apexRadius), material_(material) {
  const Vec3 along = apex - base;
  height_ = glm::length(along);
  axis_ = along / height_;
  orthonormalBasis(axis_, side1_, side2_);
  slope_ = (apexRadius_ - baseRadius_) / height_;
  normalScale_ = 1.0f / std::sqrt(1.0f + slope_ * slope_);
  zHigh_ = height_;
}

Cone Cone::segment(float zLow, float zHigh) const {
  Cone part = *this;
  part.zLow_ = zLow;
  part.zHigh_ = zHigh;
  return part;
}

Aabb Cone::bounds() const {
  // Each end circle is bounded per axis by radius·sqrt(1 - axis_i²).
  const Vec3 spread = glm::sqrt(glm::max(Vec3(0.0f), Vec3(1.0f) - axis_ * axis_));
  const bool whole = zLow_ == 0.0f && zHigh_ == height_;
  const Vec3 low = base_ + zLow_ * axis_, high = base_ + zHigh_ * axis_;
  const float lowRadius = zLow_ == 0.0f ? baseRadius_ : baseRadius_ + slope_ * zLow_;
  const float highRadius = zHigh_ == height_ ? apexRadius_ : baseRadius_ + slope_ * zHigh_;
  Aabb box;
  box.extend(low - std::max(lowRadius, 0.0f) * spread);
  box.extend(low + std::max(lowRadius, 0.0f) * spread);
  box.extend(high - std::max(highRadius, 0.0f) * spread);
  box.extend(high + std::max(highRadius, 0.0f) * spread);
  if (whole) return box;
  // A cut circle is computed in float, and a hit at the cut belongs to both neighbours: widen a
  // segment's box by a few units in the last place of its coordinates so none falls between.
  const Vec3 magnitude = glm::max(glm::abs(box.lower), glm::abs(box.upper));
  const Vec3 pad = magnitude * (8.0f * std::numeric_limits<float>::epsilon());
  box.lower -= pad;
  box.upper += pad;
  return box;
}

bool Cone::intersect(const Ray& ray, float tMax, float& tHit) const {
  // In the cone's frame (x, y across the axis, z along it from the base) the surface is
  // x² + y² = (r0 + k·z)² for 0 ≤ z ≤ h. The quadratic is solved in double precision: its
  // discriminant is a small difference of large terms for distant or axis-parallel rays, and in
  // float the lost digits put hit points inside thin cones (black shadow-acne speckles).
  const Vec3 rel = ray.origin - base_;
  const double ox = glm::dot(rel, side1_), oy = glm::dot(rel, side2_), oz = glm::dot(rel, axis_);
  const double dx = glm::dot(ray.direction, side1_), dy = glm::dot(ray.direction, side2_),
               dz = glm::dot(ray.direction, axis_);
  const double slope = slope_;
  const double radiusAtOrigin = baseRadius_ + slope * oz;
  const double a = dx * dx + dy * dy - slope * slope * dz * dz;
  const double halfB = ox * dx + oy * dy - slope * radiusAtOrigin * dz;
  const double c = ox * ox + oy * oy - radiusAtOrigin * radiusAtOrigin;

  double roots[2];
  int rootCount = 0;
  if (std::fabs(a) < 1e-12) {
    // The ray runs parallel to a generating line: one crossing at most.
    if (halfB == 0.0) return false;
    roots[rootCount++] = -c / (2.0 * halfB);
  } else {
    const double discriminant = halfB * halfB - a * c;
    if (discriminant < 0.0) return false;
    const double q = -halfB - std::copysign(std::sqrt(discriminant), halfB);
    const double t0 = q / a;
    const double t1 = q != 0.0 ? c / q : t0;
    roots[0] = std::min(t0, t1);
    roots[1] = std::max(t0, t1);
    rootCount = 2;
  }
  for (int i = 0; i < rootCount; ++i) {
    const double t = roots[i];
    if (!(t > ray.tMin && t < tMax)) continue;
    const double z = oz + t * dz;
    // The quadratic also holds the mirrored nappe beyond the tip, where the radius is negative.
    if (z < zLow_ || z > zHigh_ || baseRadius_ + slope * z < 0.0) continue;
    tHit = static_cast<float>(t);
    return true;
  }
  return false;
}

Vec3 Cone::surfacePoint(const Vec3& q, Vec3& error, Vec3& normal) const {
  const Vec3 rel = q - base_;
  const float z = glm::dot(rel, axis_);
  const Vec3 alongAxis = z * axis_;
  const Vec3 radial = rel - alongAxis;
  const float length = glm::length(radial);
  const float radius = baseRadius_ + slope_ * z;
  // Each step rounds a few times; the radial part keeps a trace of the axis (of the size of
  // those roundings of rel), which the slope turns into a distance from the surface. The bound
  // takes the largest coordinate, as those errors need not follow rel's axes.
  const float size = maxAbsComponent(rel) + std::fabs(radius);
  error =
      glm::abs(base_) * gammaBound(2) + Vec3(gammaBound(12) * (1.0f + std::fabs(slope_)) * size);
  if (!(length > 0.0f) || !(radius > 0.0f)) {  // on the axis or a pointed tip: as hit
    normal = normalAt(q);
    return q;
  }
  const Vec3 outward = radial / length;
  normal = (outward - slope_ * axis_) * normalScale_;
  return base_ + (alongAxis + radius * outward);
}

Vec3 Cone::normalAt(const Vec3& p) const {
  const Vec3 rel = p - base_;
  const float z = glm::dot(rel, axis_);
  const Vec3 radial = rel - z * axis_;
  const float radius = baseRadius_ + slope_ * z;
  // Gradient of x² + y² − (r0 + k·z)²: the radial direction tilted by the slope.
  Vec3 n = radial - slope_ * radius * axis_;
  const float len = glm::length(n);
  if (len == 0.0f) return -axis_;  // exactly at a pointed tip
  return n / len;
}

}  // namespace prism
