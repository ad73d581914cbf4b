// Vector types used throughout the renderer core. GLM supplies the arithmetic; Prism traces in
// single precision (like Embree) and keeps a few helpers GLM lacks.
#pragma once

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

namespace prism {

using Vec2 = glm::vec2;
using Vec3 = glm::vec3;
using Color = glm::vec3;  // linear RGB radiance or reflectance

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 1.0f / kPi;

inline float maxComponent(const Vec3& v) {
  return std::max(v.x, std::max(v.y, v.z));
}
inline float meanComponent(const Vec3& v) {
  return (v.x + v.y + v.z) / 3.0f;
}
inline float minComponent(const Vec3& v) {
  return std::min(v.x, std::min(v.y, v.z));
}
// |v| per component, with std::fabs: one bitwise AND each, where glm::abs (x >= 0 ? x : -x)
// compiles to a comparison and a branch per component. They differ only for -0, which
// glm::abs keeps and fabs makes +0: use it where the sign of a zero cannot matter, as in the
// error bounds (math/RayOffset.h), whose sums of magnitudes end in a max with a positive floor.
inline Vec3 absComponents(const Vec3& v) {
  return Vec3(std::fabs(v.x), std::fabs(v.y), std::fabs(v.z));
}
inline float maxAbsComponent(const Vec3& v) {
  return maxComponent(glm::abs(v));
}
inline bool isFinite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Builds two unit vectors orthogonal to unit vector n (Duff et al. 2017, "Building an
// Orthonormal Basis, Revisited"): branch-free and stable for every n.
inline void orthonormalBasis(const Vec3& n, Vec3& b1, Vec3& b2) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float b = n.x * n.y * a;
  b1 = Vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
  b2 = Vec3(b, sign + n.y * n.y * a, -n.y);
}

}  // namespace prism
