#include "image/MipPyramid.h"

#include <algorithm>
#include <utility>

namespace prism {

namespace {

// The texels of a side of `from` texels that texel i of the halved side covers, and their
// weights (the covered part of each, over the texel's width in the side below; they sum to 1).
struct Tap {
  int index;
  float weight;
};

std::vector<std::vector<Tap>> boxTaps(int from, int to) {
  std::vector<std::vector<Tap>> taps(static_cast<size_t>(to));
  const double width = static_cast<double>(from) / to;
  for (int i = 0; i < to; ++i) {
    const double begin = i * width, end = (i + 1) * width;
    for (int k = static_cast<int>(begin); k < from && k < end; ++k) {
      const double covered = std::min(end, k + 1.0) - std::max(begin, static_cast<double>(k));
      if (covered > 0.0) taps[i].push_back({k, static_cast<float>(covered / width)});
    }
  }
  return taps;
}

}  // namespace

ImageRgb halved(const ImageRgb& image) {
  const int width = std::max(1, image.width / 2), height = std::max(1, image.height / 2);
  if (image.width == 2 * width && image.height == 2 * height) {
    // Even sides (every level of a power-of-two face): each texel the mean of a 2 × 2 block,
    // in one pass.
    ImageRgb result(width, height);
    for (int y = 0; y < height; ++y) {
      const Color* top = &image.pixels[static_cast<size_t>(2 * y) * image.width];
      const Color* bottom = top + image.width;
      Color* out = &result.pixels[static_cast<size_t>(y) * width];
      for (int x = 0; x < width; ++x) {
        out[x] = 0.25f * ((top[2 * x] + top[2 * x + 1]) + (bottom[2 * x] + bottom[2 * x + 1]));
      }
    }
    return result;
  }
  const auto across = boxTaps(image.width, width), down = boxTaps(image.height, height);
  // Rows first, then columns.
  ImageRgb rows(width, image.height);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < width; ++x) {
      Color sum(0.0f);
      for (const Tap& tap : across[x]) sum += tap.weight * image.at(tap.index, y);
      rows.at(x, y) = sum;
    }
  }
  ImageRgb result(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      Color sum(0.0f);
      for (const Tap& tap : down[y]) sum += tap.weight * rows.at(x, tap.index);
      result.at(x, y) = sum;
    }
  }
  return result;
}

uint64_t mipLevelsTexels(int width, int height) {
  uint64_t texels = static_cast<uint64_t>(width) * static_cast<uint64_t>(height);
  while (width > 1 || height > 1) {
    width = std::max(1, width / 2);
    height = std::max(1, height / 2);
    texels += static_cast<uint64_t>(width) * static_cast<uint64_t>(height);
  }
  return texels;
}

std::vector<ImageRgb> mipLevels(ImageRgb image) {
  std::vector<ImageRgb> levels;
  levels.push_back(std::move(image));
  while (levels.back().width > 1 || levels.back().height > 1) {
    levels.push_back(halved(levels.back()));
  }
  return levels;
}

}  // namespace prism
