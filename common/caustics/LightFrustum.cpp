#include "caustics/LightFrustum.h"

#include <algorithm>
#include <cmath>

namespace prism {
namespace {

constexpr float kMaxHalfAngle = 75.0f * kPi / 180.0f;

LightView viewAlong(const Vec3& axis, float tanHalf) {
  LightView v;
  v.axis = glm::normalize(axis);
  orthonormalBasis(v.axis, v.right, v.up);
  v.tanHalf = tanHalf;
  return v;
}

}  // namespace

LightFrustum::LightFrustum(const Vec3& light, const std::vector<CasterBounds>& casters,
                           int resolution)
    : light_(light), n_(resolution) {
  if (casters.empty() || resolution <= 0) return;
  bool needCube = false;
  Vec3 sum(0.0f);
  for (const CasterBounds& c : casters) {
    if (c.plane || glm::length(c.center - light) <= c.radius * 1.001f) {
      needCube = true;
      break;
    }
    sum += glm::normalize(c.center - light);
  }
  float half = 0.0f;
  if (!needCube && glm::length(sum) > 1e-3f) {
    const Vec3 axis = glm::normalize(sum);
    for (const CasterBounds& c : casters) {
      const float d = glm::length(c.center - light);
      const float toCenter =
          std::acos(std::clamp(glm::dot(axis, (c.center - light) / d), -1.0f, 1.0f));
      half = std::max(half, toCenter + std::asin(std::min(1.0f, c.radius / d)));
    }
    needCube = half > kMaxHalfAngle;
    // A texel's margin: the square grid's inscribed cone must hold the casters.
    if (!needCube) views_.push_back(viewAlong(axis, std::tan(half) * (1.0f + 2.0f / n_)));
  } else {
    needCube = true;
  }
  if (needCube) {
    views_.clear();
    // Each face is its own square: axis ±X, ±Y, ±Z with a 90° field; texels at the shared
    // edges belong to whichever face projects them with |x|,|y| ≤ 1.
    const Vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const Vec3& a : axes) views_.push_back(viewAlong(a, 1.0f));
  }
  for (const LightView& v : views_) {
    columns_.push_back({simd::Float4{v.axis.x, v.right.x, v.up.x, 0.0f},
                        simd::Float4{v.axis.y, v.right.y, v.up.y, 0.0f},
                        simd::Float4{v.axis.z, v.right.z, v.up.z, 0.0f},
                        static_cast<float>(n_) / (2.0f * v.tanHalf)});
  }
}

float LightFrustum::halfAngleDegrees() const {
  if (views_.empty()) return 0.0f;
  return cube() ? 45.0f : std::atan(views_[0].tanHalf) * 180.0f / kPi;
}

Vec3 LightFrustum::direction(int view, float x, float y) const {
  const LightView& v = views_[static_cast<size_t>(view)];
  const float s = 2.0f * v.tanHalf / static_cast<float>(n_);
  const float u = -v.tanHalf + x * s;
  const float w = -v.tanHalf + y * s;
  return glm::normalize(v.axis + u * v.right + w * v.up);
}

double LightFrustum::texelSolidAngle(int i, int j) const {
  // dΩ = dA / (1 + u² + w²)^{3/2} on the plane at distance 1; same for every view's texel (i, j).
  const double t = views_[0].tanHalf;
  const double s = 2.0 * t / n_;
  const double u = -t + (i + 0.5) * s, w = -t + (j + 0.5) * s;
  const double r2 = 1.0 + u * u + w * w;
  return s * s / (r2 * std::sqrt(r2));
}

std::optional<LightSpacePoint> LightFrustum::project(const Vec3& p) const {
  const Vec3 d = p - light_;
  const float dist = glm::length(d);
  if (!(dist > 0.0f)) return std::nullopt;
  // Lane by lane (d.x·a.x + d.y·a.y) + d.z·a.z: glm::dot's order, so the same roundings.
  const simd::Float4 dx{d.x, d.x, d.x, d.x}, dy{d.y, d.y, d.y, d.y}, dz{d.z, d.z, d.z, d.z};
  for (size_t k = 0; k < views_.size(); ++k) {
    const ViewColumns& c = columns_[k];
    const simd::Float4 along = c.x * dx + c.y * dy + c.z * dz;  // axis, right, up
    const float z = along[0];
    if (!(z > 0.0f)) continue;
    const float tanHalf = views_[k].tanHalf;
    const float u = along[1] / z, w = along[2] / z;
    if (std::abs(u) > tanHalf || std::abs(w) > tanHalf) continue;
    LightSpacePoint out;
    out.view = static_cast<int>(k);
    out.x = std::clamp((u + tanHalf) * c.scale, 0.0f, static_cast<float>(n_) - 1e-3f);
    out.y = std::clamp((w + tanHalf) * c.scale, 0.0f, static_cast<float>(n_) - 1e-3f);
    out.distance = dist;
    return out;
  }
  return std::nullopt;
}

}  // namespace prism
