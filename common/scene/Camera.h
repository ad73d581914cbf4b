// Pinhole perspective or orthographic camera. Pixel (0, 0) is the top-left corner of the image;
// image x runs along the camera's right vector, image y down its up vector.
#pragma once

#include <optional>

#include "math/Ray.h"
#include "scene/SceneDescription.h"

namespace prism {

class Camera {
 public:
  Camera(const CameraDesc& desc, int imageWidth, int imageHeight);

  // A unit-direction ray through the image-plane point (x, y), in pixels.
  Ray generateRay(float x, float y) const;
  // The image-plane point, in pixels, that world point p projects to; nothing when p lies
  // behind the camera.
  std::optional<Vec2> project(const Vec3& p) const;

 private:
  Projection projection_;
  Vec3 position_;
  Vec3 forward_, right_, up_;
  float halfWidth_;  // perspective: tan of the half angle × aspect; orthographic: world units
  float halfHeight_;
  float invWidth_, invHeight_;
  float nearClip_;
};

}  // namespace prism
