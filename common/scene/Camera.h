// Pinhole perspective or orthographic camera. Pixel (0, 0) is the top-left corner of the image;
// image x runs along the camera's right vector, image y down its up vector.
#pragma once

#include <optional>

#include "math/Ray.h"
#include "math/RayCone.h"
#include "math/RayDifferential.h"
#include "scene/SceneDescription.h"

namespace prism {

class Camera {
 public:
  Camera(const CameraDesc& desc, int imageWidth, int imageHeight);

  // A unit-direction ray through the image-plane point (x, y), in pixels.
  Ray generateRay(float x, float y) const;
  // rays[i] = generateRay(x[i], y[i]) for `count` points (a pixel block's), four at a time as
  // vector lanes: the same operations in the same order, so the same rays to the bit.
  void generateRays(const float* x, const float* y, int count, Ray* rays) const;
  // How ray (from generateRay) changes per pixel step in x and in y: the pixel's own footprint
  // for every sample of it, not a 1/spp share (with shares a focus narrower than a pixel could
  // fall between its samples' footprints or into a neighbour's: docs/accuracy.md).
  RayDifferential pixelDifferential(const Ray& ray) const;
  // The ray's cone (math/RayCone.h): a pixel wide where the ray meets the image plane at unit
  // distance ahead (perspective: spread the pixel's angle along the ray, width 0), or a pixel's
  // width wide throughout (orthographic: spread 0).
  RayCone pixelCone(const Ray& ray) const;
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
