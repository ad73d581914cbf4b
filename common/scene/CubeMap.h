// Environment cube map: six square images around the scene, looked up by direction for
// escaping rays (background, reflections, refractions). Face order and orientation follow the
// OpenGL convention (+X, -X, +Y, -Y, +Z, -Z), so maps made for OpenGL load unchanged.
#pragma once

#include <optional>

#include "scene/SceneDescription.h"

namespace prism {

class CubeMap {
 public:
  // By value: a description the caller no longer needs moves in (six faces, megabytes).
  explicit CubeMap(CubeMapDesc desc);

  // Bilinearly filtered radiance seen along direction (need not be unit length).
  Color lookup(const Vec3& direction) const;

  // Where a direction meets the cube: the face (in the order above) and the point on its image
  // in texel units, texel centres at whole numbers (each coordinate within [-0.5, size - 0.5]);
  // nothing for the zero direction. lookup() filters the four texels around it.
  struct FacePoint {
    int face;
    float s, t;  // column and row
  };
  std::optional<FacePoint> facePoint(const Vec3& direction) const;

 private:
  Color texel(int face, int x, int y) const;

  std::array<ImageRgb, 6> faces_;
  float scale_;
};

}  // namespace prism
