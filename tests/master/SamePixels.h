// Whether two images are the same image bit for bit: the end-to-end tests' check that ranks,
// threads, tiles and instruction sets leave the pixels alone.
#pragma once

#include <cstring>

#include "image/ImageRgb.h"

namespace prism::test {

inline bool samePixels(const ImageRgb& a, const ImageRgb& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Color)) == 0;
}

}  // namespace prism::test
