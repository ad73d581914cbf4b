#include "scene/Camera.h"

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
