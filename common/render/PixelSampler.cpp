#include "render/PixelSampler.h"

#include <cmath>

namespace prism {

PixelSampler::PixelSampler(int samplesPerPixel, bool jitterSingleSample)
    : count_(samplesPerPixel), jitterSingle_(jitterSingleSample) {
  // The largest divisor not above √spp gives the squarest grid with exactly spp strata.
  rows_ = static_cast<int>(std::sqrt(static_cast<double>(samplesPerPixel)));
  while (rows_ > 1 && samplesPerPixel % rows_ != 0) --rows_;
  if (rows_ < 1) rows_ = 1;
  columns_ = samplesPerPixel / rows_;
}

Vec2 PixelSampler::offset(int i, Pcg32& rng) const {
  if (count_ == 1 && !jitterSingle_) return Vec2(0.5f);
  const int column = i % columns_;
  const int row = i / columns_;
  const float jitterX = rng.nextFloat();
  const float jitterY = rng.nextFloat();
  return Vec2((static_cast<float>(column) + jitterX) / static_cast<float>(columns_),
              (static_cast<float>(row) + jitterY) / static_cast<float>(rows_));
}

}  // namespace prism
