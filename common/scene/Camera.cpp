#include "scene/Camera.h"

#include <algorithm>
#include <new>

#include "math/RayRows.h"
#include "math/Simd.h"

namespace prism {

Camera::Camera(const CameraDesc& desc, int imageWidth, int imageHeight)
    : projection_(desc.projection),
      position_(desc.position),
      invWidth_(1.0f / static_cast<float>(imageWidth)),
      invHeight_(1.0f / static_cast<float>(imageHeight)),
      nearClip_(desc.nearClip) {
  forward_ = glm::normalize(desc.lookAt - desc.position);
  right_ = glm::normalize(glm::cross(forward_, desc.up));
  up_ = glm::cross(right_, forward_);
  const float aspect = static_cast<float>(imageWidth) / static_cast<float>(imageHeight);
  if (projection_ == Projection::Perspective) {
    halfHeight_ = std::tan(0.5f * glm::radians(desc.fovDegrees));
    halfWidth_ = halfHeight_ * aspect;
  } else {
    halfWidth_ = 0.5f * desc.width;
    halfHeight_ = halfWidth_ / aspect;
  }
}

Ray Camera::generateRay(float x, float y) const {
  const float sx = (2.0f * x * invWidth_ - 1.0f) * halfWidth_;
  const float sy = (1.0f - 2.0f * y * invHeight_) * halfHeight_;
  Ray ray;
  if (projection_ == Projection::Perspective) {
    ray.origin = position_;
    ray.direction = glm::normalize(forward_ + sx * right_ + sy * up_);
    // The near plane is perpendicular to the view axis, so oblique rays start further out.
    ray.tMin = nearClip_ / glm::dot(ray.direction, forward_);
  } else {
    ray.origin = position_ + sx * right_ + sy * up_;
    ray.direction = forward_;
    ray.tMin = nearClip_;
  }
  return ray;
}

void Camera::generateRays(const float* x, const float* y, int count, Ray* rays) const {
  using simd::Float4;
  int first = 0;
  if (projection_ == Projection::Perspective) {
    for (; first + 4 <= count; first += 4) {
      // generateRay's arithmetic, lane by lane (glm::normalize is v · (1 / √(v·v)), glm::dot
      // (a.x·b.x + a.y·b.y) + a.z·b.z).
      const Float4 sx = (2.0f * simd::load<Float4>(x + first) * invWidth_ - 1.0f) * halfWidth_;
      const Float4 sy = (1.0f - 2.0f * simd::load<Float4>(y + first) * invHeight_) * halfHeight_;
      Float4 d[3];
      for (int a = 0; a < 3; ++a) d[a] = (forward_[a] + sx * right_[a]) + sy * up_[a];
      const Float4 scale = 1.0f / simd::sqrtLanes((d[0] * d[0] + d[1] * d[1]) + d[2] * d[2]);
      for (int a = 0; a < 3; ++a) d[a] = d[a] * scale;
      const Float4 tMin = nearClip_ / ((d[0] * forward_.x + d[1] * forward_.y) + d[2] * forward_.z);
      const float end = Ray{}.tMax;  // the ray's own default: no end
      const Vec3& o = position_;
      const Float4 origin[3] = {Float4{o.x, o.x, o.x, o.x}, Float4{o.y, o.y, o.y, o.y},
                                Float4{o.z, o.z, o.z, o.z}};
      simd::storeRays(origin, d, tMin, Float4{end, end, end, end}, rays + first);
    }
  }
  // The rest made in their places: assigned from a returned Ray, a ray was copied with 16-byte
  // loads before generateRay's 4-byte stores had landed (a store-forwarding stall).
  for (; first < count; ++first) ::new (&rays[first]) Ray(generateRay(x[first], y[first]));
}

RayDifferential Camera::pixelDifferential(const Ray& ray) const {
  // generateRay's image-plane point moves by these per pixel.
  const Vec3 stepX = (2.0f * halfWidth_ * invWidth_) * right_;
  const Vec3 stepY = (-2.0f * halfHeight_ * invHeight_) * up_;
  RayDifferential d;
  d.valid = true;
  if (projection_ != Projection::Perspective) {
    d.dOdx = stepX;
    d.dOdy = stepY;
    return d;
  }
  // The direction is normalize(u) with u·forward = 1: dD = (du − D(D·du)) / |u|.
  const Vec3& D = ray.direction;
  const float invLength = glm::dot(D, forward_);
  d.dDdx = (stepX - D * glm::dot(D, stepX)) * invLength;
  d.dDdy = (stepY - D * glm::dot(D, stepY)) * invLength;
  return d;
}

RayCone Camera::pixelCone(const Ray&) const {
  // One angle for every ray, the pixel's at the image's centre (as the paper takes it): off
  // the axis a pixel subtends a little less, which only moves a lookup towards a finer level.
  const float pixel = std::max(2.0f * halfWidth_ * invWidth_, 2.0f * halfHeight_ * invHeight_);
  if (projection_ != Projection::Perspective) return {pixel, 0.0f};
  return {0.0f, pixel};
}

std::optional<Vec2> Camera::project(const Vec3& p) const {
  const Vec3 d = p - position_;
  float sx = glm::dot(d, right_), sy = glm::dot(d, up_);
  if (projection_ == Projection::Perspective) {
    const float z = glm::dot(d, forward_);
    if (!(z > 0.0f)) return std::nullopt;
    sx /= z;
    sy /= z;
  }
  return Vec2((sx / halfWidth_ + 1.0f) * 0.5f / invWidth_,
              (1.0f - sy / halfHeight_) * 0.5f / invHeight_);
}

}  // namespace prism
