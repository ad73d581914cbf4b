#include "image/ImageError.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace prism {
namespace {

void requireSameSize(const ImageRgb& a, const ImageRgb& b, const char* what) {
  if (a.width != b.width || a.height != b.height) {
    throw std::invalid_argument(std::string(what) + " is " + std::to_string(a.width) + "x" +
                                std::to_string(a.height) + ", the reference " +
                                std::to_string(b.width) + "x" + std::to_string(b.height));
  }
}

// Rec. 709 luminance, the weights the sRGB primaries call for.
double luminance(const Color& c) {
  return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
}

}  // namespace

ImageError imageError(const ImageRgb& test, const ImageRgb& reference, const ImageRgb& base,
                      const PixelMask& mask) {
  requireSameSize(test, reference, "the test image");
  const bool withBase = !base.pixels.empty();
  if (withBase) requireSameSize(base, reference, "the frame without caustics");
  if (!mask.empty() && mask.size() != reference.pixels.size()) {
    throw std::invalid_argument("the mask does not match the image size");
  }
  ImageError e;
  double squared = 0.0, relative = 0.0, referenceSum = 0.0, testFlux = 0.0, referenceFlux = 0.0;
  for (size_t i = 0; i < reference.pixels.size(); ++i) {
    if (!mask.empty() && !mask[i]) continue;
    ++e.pixels;
    for (int c = 0; c < 3; ++c) {
      const double t = test.pixels[i][c], r = reference.pixels[i][c];
      const double d = t - r;
      squared += d * d;
      relative += d * d / (r * r + 0.01);
      referenceSum += r;
      e.maxError = std::max(e.maxError, std::abs(d));
      if (withBase) {
        testFlux += t - base.pixels[i][c];
        referenceFlux += r - base.pixels[i][c];
      }
    }
  }
  const double values = 3.0 * static_cast<double>(e.pixels);
  if (values == 0.0) {  // an empty region has no error to speak of, not an error of 0
    e.rmse = e.relRmse = e.mrse = e.maxError = std::numeric_limits<double>::quiet_NaN();
  } else {
    e.rmse = std::sqrt(squared / values);
    e.mrse = relative / values;
    const double mean = referenceSum / values;
    e.relRmse = mean > 0.0 ? e.rmse / mean : std::numeric_limits<double>::quiet_NaN();
  }
  e.fluxRatio = withBase && referenceFlux > 0.0 ? testFlux / referenceFlux
                                                : std::numeric_limits<double>::quiet_NaN();
  return e;
}

PixelMask causticMask(const ImageRgb& reference, const ImageRgb& base, double fraction, int grow) {
  requireSameSize(base, reference, "the frame without caustics");
  const size_t n = reference.pixels.size();
  std::vector<double> caustic(n);
  std::vector<double> positive;
  for (size_t i = 0; i < n; ++i) {
    caustic[i] = luminance(reference.pixels[i] - base.pixels[i]);
    if (caustic[i] > 0.0) positive.push_back(caustic[i]);
  }
  PixelMask seed(n, 0);
  if (positive.empty()) return seed;
  const size_t rank = std::min(positive.size() - 1, positive.size() * 99 / 100);
  std::nth_element(positive.begin(), positive.begin() + static_cast<ptrdiff_t>(rank),
                   positive.end());
  const double threshold = fraction * positive[rank];
  for (size_t i = 0; i < n; ++i) seed[i] = caustic[i] > 0.0 && caustic[i] >= threshold;
  if (grow <= 0) return seed;
  // A square dilation, separable: rows first, then columns.
  const int w = reference.width, h = reference.height;
  PixelMask rows(n, 0), grown(n, 0);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (!seed[static_cast<size_t>(y) * w + x]) continue;
      for (int dx = std::max(0, x - grow); dx <= std::min(w - 1, x + grow); ++dx)
        rows[static_cast<size_t>(y) * w + dx] = 1;
    }
  }
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (!rows[static_cast<size_t>(y) * w + x]) continue;
      for (int dy = std::max(0, y - grow); dy <= std::min(h - 1, y + grow); ++dy)
        grown[static_cast<size_t>(dy) * w + x] = 1;
    }
  }
  return grown;
}

size_t maskedPixels(const PixelMask& mask) {
  return static_cast<size_t>(std::count_if(mask.begin(), mask.end(), [](uint8_t m) { return m; }));
}

}  // namespace prism
