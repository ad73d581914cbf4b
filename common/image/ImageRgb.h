// A linear RGB float image, row-major with (0, 0) at the top left.
#pragma once

#include <cstddef>
#include <vector>

#include "math/Vec.h"

namespace prism {

struct ImageRgb {
  int width = 0;
  int height = 0;
  std::vector<Color> pixels;

  ImageRgb() = default;
  ImageRgb(int w, int h) : width(w), height(h), pixels(static_cast<size_t>(w) * h, Color(0.0f)) {}

  Color& at(int x, int y) { return pixels[static_cast<size_t>(y) * width + x]; }
  const Color& at(int x, int y) const { return pixels[static_cast<size_t>(y) * width + x]; }
};

}  // namespace prism
