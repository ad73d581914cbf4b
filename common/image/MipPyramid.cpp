#include "image/MipPyramid.h"

#include <algorithm>
#include <array>
#include <utility>

#include "util/HugePages.h"

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

// The level above a source of width × height texels read by source.at(x, y) (a Color).
template <class Source>
ImageRgb halvedFrom(const Source& image) {
  const int width = std::max(1, image.width / 2), height = std::max(1, image.height / 2);
  if (image.width == 2 * width && image.height == 2 * height) {
    // Even sides (every level of a power-of-two face): each texel the mean of a 2 × 2 block,
    // in one pass, appended (not written over zeros: the zeroing and its page faults cost as
    // much as the averaging).
    ImageRgb result;
    result.width = width;
    result.height = height;
    reserveOnHugePages(result.pixels, static_cast<size_t>(width) * height);
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        result.pixels.push_back(0.25f *
                                ((image.at(2 * x, 2 * y) + image.at(2 * x + 1, 2 * y)) +
                                 (image.at(2 * x, 2 * y + 1) + image.at(2 * x + 1, 2 * y + 1))));
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

// An 8-bit image read as radiance, texel by texel (no float copy of a whole face).
struct SrgbSource {
  const SrgbImage& image;
  const std::array<float, 256>& linear = linearOfSrgbByte();
  int width = image.width, height = image.height;
  Color at(int x, int y) const {
    const uint8_t* p = &image.rgb[3 * (static_cast<size_t>(y) * width + x)];
    return Color(linear[p[0]], linear[p[1]], linear[p[2]]);
  }
};

}  // namespace

ImageRgb halved(const ImageRgb& image) {
  return halvedFrom(image);
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

std::vector<SrgbTexels> srgbMipLevels(const SrgbImage& image) {
  std::vector<SrgbTexels> levels;
  levels.push_back(packedTexels(image));
  if (image.width <= 1 && image.height <= 1) return levels;
  // Each level averages the radiance of the level below before that was rounded to bytes, so
  // the roundings do not add up over the levels; only the bytes are kept.
  ImageRgb level = halvedFrom(SrgbSource{image});
  for (;;) {
    levels.push_back(packedTexels(level));
    if (level.width <= 1 && level.height <= 1) return levels;
    level = halved(level);
  }
}

}  // namespace prism
