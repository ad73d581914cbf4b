#include "image/Thumbnail.h"

#include <algorithm>
#include <cmath>

namespace prism {

PixelRect maskBounds(const PixelMask& mask, int width, int height, double margin) {
  int x0 = width, y0 = height, x1 = -1, y1 = -1;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      if (!mask.empty() && mask[static_cast<size_t>(y) * width + x]) {
        x0 = std::min(x0, x);
        x1 = std::max(x1, x);
        y0 = std::min(y0, y);
        y1 = std::max(y1, y);
      }
    }
  }
  if (x1 < 0) return {0, 0, width, height};
  const int padX = static_cast<int>(std::ceil(margin * (x1 - x0 + 1)));
  const int padY = static_cast<int>(std::ceil(margin * (y1 - y0 + 1)));
  x0 = std::max(0, x0 - padX);
  y0 = std::max(0, y0 - padY);
  x1 = std::min(width - 1, x1 + padX);
  y1 = std::min(height - 1, y1 + padY);
  return {x0, y0, x1 - x0 + 1, y1 - y0 + 1};
}

ImageRgb thumbnail(const ImageRgb& image, const PixelRect& rect, int maxHeight) {
  const double scale = std::max(1.0, static_cast<double>(rect.height) / std::max(maxHeight, 1));
  const int w = std::max(1, static_cast<int>(std::lround(rect.width / scale)));
  const int h = std::max(1, static_cast<int>(std::lround(rect.height / scale)));
  ImageRgb out(w, h);
  for (int y = 0; y < h; ++y) {
    const int sy0 = rect.y + static_cast<int>(y * scale);
    const int sy1 = std::max(
        sy0 + 1, std::min(rect.y + rect.height, rect.y + static_cast<int>((y + 1) * scale)));
    for (int x = 0; x < w; ++x) {
      const int sx0 = rect.x + static_cast<int>(x * scale);
      const int sx1 = std::max(
          sx0 + 1, std::min(rect.x + rect.width, rect.x + static_cast<int>((x + 1) * scale)));
      Color sum(0.0f);
      for (int sy = sy0; sy < sy1; ++sy)
        for (int sx = sx0; sx < sx1; ++sx) sum += image.at(sx, sy);
      out.at(x, y) = sum / static_cast<float>((sy1 - sy0) * (sx1 - sx0));
    }
  }
  return out;
}

}  // namespace prism
