// How far a rendered image is from a reference: the error numbers `prism sweep` charts against
// time. All work on linear radiance, per channel, over the pixels a mask selects.
//   rmse      sqrt(mean((t − r)²))
//   relRmse   rmse / mean(r): the RMSE as a fraction of the region's mean radiance
//   mrse      mean((t − r)² / (r² + 0.01)): relative MSE in pbrt's convention (imgtool's MRSE);
//             the 0.01 keeps black reference pixels from dominating
//   maxError  max |t − r|
//   fluxRatio Σ(t − base) / Σ(r − base): the caustic light the test image has, as a fraction of
//             the reference's, where base is the same frame without caustics (1 = all of it)
#pragma once

#include <cstdint>
#include <vector>

#include "image/ImageRgb.h"

namespace prism {

struct ImageError {
  double rmse = 0.0;
  double relRmse = 0.0;
  double mrse = 0.0;
  double maxError = 0.0;
  double fluxRatio = 0.0;  // NaN when the reference has no caustic light in the region
  size_t pixels = 0;       // pixels compared
};

// One byte per pixel, nonzero where the pixel counts.
using PixelMask = std::vector<uint8_t>;

// Compares test with reference over the mask (empty: every pixel; one that selects nothing
// gives NaN throughout). base is the frame without caustics, for the flux ratio (empty image:
// no flux ratio, NaN). Throws std::invalid_argument when the sizes differ.
ImageError imageError(const ImageRgb& test, const ImageRgb& reference, const ImageRgb& base = {},
                      const PixelMask& mask = {});

// The caustic region: pixels whose caustic light (reference − base, luminance) is at least
// `fraction` of the 99th percentile of the positive caustic light, grown by `grow` pixels in
// every direction so that light an estimator smears past the edge is counted too. Empty (all
// zero) when the reference holds no caustic light.
PixelMask causticMask(const ImageRgb& reference, const ImageRgb& base, double fraction = 0.05,
                      int grow = 2);

// Pixels the mask selects.
size_t maskedPixels(const PixelMask& mask);

}  // namespace prism
