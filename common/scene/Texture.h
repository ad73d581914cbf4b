// A material's texture as the renderer reads it: the image's mip pyramid (image/MipPyramid.h),
// packed sRGB bytes where the file held 8-bit sRGB (as the sky keeps them), else floats, read
// with repeat wrapping, bilinear within a level and linear between two (trilinear), at the level
// whose texels match the ray cone's width where it meets the surface (math/RayCone.h).
#pragma once

#include <vector>

#include "image/ImageRgb.h"
#include "image/SrgbImage.h"
#include "scene/SceneDescription.h"

namespace prism {

class Texture {
 public:
  // By value: the image moves into the pyramid's finest level.
  explicit Texture(TextureDesc desc);

  // The texture at coordinates uv (repeating; v = 0 is the bottom row), averaged over a square
  // footprint `width` texture units wide (a ray cone's width times the surface's uvPerWorld):
  // trilinear between the two levels about log2(width · size). width ≤ 0: the finest level,
  // bilinear.
  Color lookup(Vec2 uv, float width) const;
  // Bilinear lookup of one level (repeating).
  Color bilinear(int level, Vec2 uv) const;
  // The level a footprint of `width` texture units reads (fractional: the blend between two).
  float levelOfDetail(float width) const;

  int levelCount() const;
  int width(int level = 0) const;
  int height(int level = 0) const;
  bool keepsBytes() const { return !srgbLevels_.empty(); }

 private:
  std::vector<ImageRgb> linearLevels_;
  std::vector<SrgbTexels> srgbLevels_;
};

}  // namespace prism
