// A rectangle of the image and the pixels rendered for it. These are the units of work the
// master hands out and the slaves send back.
#pragma once

#include <cstdint>
#include <vector>

#include "math/Vec.h"
#include "render/RayCounters.h"

namespace prism {

struct TileRect {
  int x = 0;
  int y = 0;
  int width = 0;
  int height = 0;

  int pixelCount() const { return width * height; }
};

struct TileResult {
  uint32_t tileIndex = 0;
  TileRect rect;
  std::vector<Color> pixels;  // row-major within the tile
  RayCounters rays;
  double seconds = 0.0;  // wall time spent rendering this tile
};

}  // namespace prism
