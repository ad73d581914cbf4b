// 8-bit sRGB images: what PNG files hold (3 bytes a pixel), and the packed texels a cube map
// keeps of them (4 bytes a texel, one aligned load). Kept as bytes rather than linear floats they
// are a third (a quarter, packed) of the size on the wire, in memory and in the caches; a byte
// becomes radiance through a 256-entry table.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "image/ImageRgb.h"
#include "util/HugePages.h"

namespace prism {

// R, G, B bytes per pixel, sRGB-encoded, rows from the top.
struct SrgbImage {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgb;

  bool empty() const { return width == 0 || height == 0; }
};

// Linear radiance of each byte value: byte·(1/255) through the sRGB curve (as OpenImageIO turns
// bytes into floats, then linearises).
const std::array<float, 256>& linearOfSrgbByte();

// The image as linear radiance (exactly what readImage gives for the same file).
ImageRgb linearFromSrgb(const SrgbImage& image);

// A level of a cube face's mip pyramid as packed sRGB texels: R in the low byte, then G and B,
// the high byte unused.
struct SrgbTexels {
  int width = 0;
  int height = 0;
  // On huge pages where a level is 2 MiB or more: a 1024² face's finest level read in 4 KiB
  // pages missed the TLB on most lookups.
  std::vector<uint32_t, HugePageAllocator<uint32_t>> texels;

  Color at(int x, int y) const { return decode(texels[static_cast<size_t>(y) * width + x]); }
  static Color decode(uint32_t texel) {
    const std::array<float, 256>& linear = linearOfSrgbByte();
    return Color(linear[texel & 0xff], linear[(texel >> 8) & 0xff], linear[(texel >> 16) & 0xff]);
  }
};

// The image's bytes packed, unchanged.
SrgbTexels packedTexels(const SrgbImage& image);
// Radiance encoded to the nearest sRGB byte (clamped to [0, 1]), packed.
SrgbTexels packedTexels(const ImageRgb& image);

}  // namespace prism
