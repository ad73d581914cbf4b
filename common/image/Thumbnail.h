// Small pictures of a region of an image, for the thumbnail strips of `prism sweep`.
#pragma once

#include "image/ImageError.h"
#include "image/ImageRgb.h"

namespace prism {

struct PixelRect {
  int x = 0, y = 0, width = 0, height = 0;
  bool empty() const { return width <= 0 || height <= 0; }
};

// The smallest rectangle holding every pixel the mask selects, grown by `margin` of its size on
// each side and clipped to the image; the whole image when the mask selects nothing.
PixelRect maskBounds(const PixelMask& mask, int width, int height, double margin = 0.15);

// The rectangle of the image, box-filtered down so that it is at most maxHeight pixels tall
// (never enlarged). The rectangle must lie inside the image.
ImageRgb thumbnail(const ImageRgb& image, const PixelRect& rect, int maxHeight);

}  // namespace prism
