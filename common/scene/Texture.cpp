#include "scene/Texture.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "image/MipPyramid.h"
#include "math/FloorToInt.h"

namespace prism {

namespace {

// x wrapped into [0, size): repeat wrapping for texel indices.
inline int wrap(int x, int size) {
  const int r = x % size;
  return r < 0 ? r + size : r;
}

template <class Texels>
Color bilinearOf(const Texels& image, Vec2 uv) {
  // Texel centres at half-integers; v = 0 is the bottom row, the image's rows run from the top.
  const float s = uv.x * static_cast<float>(image.width) - 0.5f;
  const float t = (1.0f - uv.y) * static_cast<float>(image.height) - 0.5f;
  // The floor taken in double: far-off coordinates (a tiling of thousands) keep their fraction.
  const double fs = std::floor(static_cast<double>(s)), ft = std::floor(static_cast<double>(t));
  const float fx = s - static_cast<float>(fs), fy = t - static_cast<float>(ft);
  const int x0 = wrap(static_cast<int>(std::fmod(fs, image.width)), image.width);
  const int y0 = wrap(static_cast<int>(std::fmod(ft, image.height)), image.height);
  const int x1 = x0 + 1 == image.width ? 0 : x0 + 1;
  const int y1 = y0 + 1 == image.height ? 0 : y0 + 1;
  const Color top = glm::mix(image.at(x0, y0), image.at(x1, y0), fx);
  const Color bottom = glm::mix(image.at(x0, y1), image.at(x1, y1), fx);
  return glm::mix(top, bottom, fy);
}

}  // namespace

Texture::Texture(TextureDesc desc) {
  if (desc.keptAsBytes()) {
    srgbLevels_ = srgbMipLevels(desc.srgb);
  } else {
    linearLevels_ = mipLevels(std::move(desc.linear));
  }
}

int Texture::levelCount() const {
  return static_cast<int>(keepsBytes() ? srgbLevels_.size() : linearLevels_.size());
}
int Texture::width(int level) const {
  return keepsBytes() ? srgbLevels_[level].width : linearLevels_[level].width;
}
int Texture::height(int level) const {
  return keepsBytes() ? srgbLevels_[level].height : linearLevels_[level].height;
}

Color Texture::bilinear(int level, Vec2 uv) const {
  return keepsBytes() ? bilinearOf(srgbLevels_[level], uv) : bilinearOf(linearLevels_[level], uv);
}

float Texture::levelOfDetail(float width) const {
  // The footprint in finest-level texels, along the texture's longer side (as OpenGL's λ takes
  // the longer of the footprint's axes).
  const float texels = width * static_cast<float>(std::max(this->width(0), height(0)));
  return texels > 1.0f ? std::log2(texels) : 0.0f;
}

Color Texture::lookup(Vec2 uv, float width) const {
  if (!(width > 0.0f)) return bilinear(0, uv);
  const int top = levelCount() - 1;
  const float lod = std::min(levelOfDetail(width), static_cast<float>(top));
  const int level = static_cast<int>(lod);
  const float weight = lod - static_cast<float>(level);  // of the coarser level
  const Color lower = bilinear(level, uv);
  if (level == top || weight == 0.0f) return lower;
  return glm::mix(lower, bilinear(level + 1, uv), weight);
}

}  // namespace prism
