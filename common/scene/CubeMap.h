// Environment cube map: six square images around the scene, looked up by direction for
// escaping rays (background, reflections, refractions). Face order and orientation follow the
// OpenGL convention (+X, -X, +Y, -Y, +Z, -Z), so maps made for OpenGL load unchanged.
//
// Each face keeps a mip pyramid (image/MipPyramid.h, box filtered), built once with the scene:
// as packed sRGB bytes where the faces came from 8-bit files (a quarter of floats' size in the
// caches), else as floats.
// A ray that carries its footprint (how its direction changes per pixel) reads the levels whose
// texels match the footprint, blending the two nearest (trilinear, as OpenGL's
// LINEAR_MIPMAP_LINEAR picks them); a ray without one reads the finest level. Bilinear blends
// that reach past a face's edge read the neighbouring face's texels there (OpenGL's seamless
// cube-map filtering), so coarse levels show no seams along the cube's edges.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "scene/SceneDescription.h"

namespace prism {

class CubeMap {
 public:
  // By value: a description the caller no longer needs moves in (six faces, megabytes).
  explicit CubeMap(CubeMapDesc desc);

  // Bilinearly filtered radiance of the finest level seen along direction (need not be unit
  // length): for rays without a footprint (photons, ended differentials).
  Color lookup(const Vec3& direction) const;
  // Radiance averaged over the footprint of a ray of unit direction d whose direction changes
  // by dDdx and dDdy per pixel (RayDifferential): trilinear between the two levels about
  // levelOfDetail(). Zero changes give lookup(d).
  Color lookup(const Vec3& d, const Vec3& dDdx, const Vec3& dDdy) const;
  // Radiance averaged over a cone of directions about unit direction d, `spread` radians wide
  // (a ray cone's, math/RayCone.h): the same trilinear lookup, the footprint's width on d's face
  // spread/ma² (the gnomonic projection stretches a small angle by 1/cos² along the radius, the
  // longer axis). A zero spread gives lookup(d).
  Color lookup(const Vec3& d, float spread) const;
  // log2 of the footprint's width in finest-level texels (OpenGL's λ, the longer of the two
  // per-pixel steps projected onto d's face); below 0 where a pixel is narrower than a texel,
  // -infinity without change.
  float levelOfDetail(const Vec3& d, const Vec3& dDdx, const Vec3& dDdy) const;

  // Where a direction meets the cube: the face (in the order above) and the point on its image
  // in texel units, texel centres at whole numbers (each coordinate within [-0.5, size - 0.5]);
  // nothing for the zero direction. lookup() filters the four texels around it.
  struct FacePoint {
    int face;
    float s, t;  // column and row
  };
  std::optional<FacePoint> facePoint(const Vec3& direction) const;

  // Level 0 is the finest (the faces as loaded), the last 1x1; each level is
  // halved(the level below).
  int levelCount() const;
  struct FaceSize {
    int width, height;
  };
  FaceSize faceSize(int level, int face) const;
  // Texel (x, y) of a face at a level, inside the face (no scale applied).
  Color texelAt(int level, int face, int x, int y) const;
  // Whether the faces are kept as packed sRGB bytes (read from 8-bit files) rather than floats.
  bool keepsBytes() const { return !srgbLevels_.empty(); }
  // Bilinearly filtered radiance of one level (no scale applied); u, v in [0, 1] across the
  // face, as facePoint's s, t over the face's size in texels. Texels past the face's edge are
  // read from the neighbouring face.
  Color bilinear(int level, int face, float u, float v) const;

 private:
  // The pyramids of the six faces, level by level: one of the two is empty.
  std::vector<std::array<ImageRgb, 6>> linearLevels_;
  std::vector<std::array<SrgbTexels, 6>> srgbLevels_;
  float scale_;
};

}  // namespace prism
