// Stratified supersampling positions within a pixel. spp samples cover an nx × ny grid of
// strata (nx·ny = spp, as square as spp's factors allow), one jittered sample per stratum; one
// sample per pixel goes through the pixel centre, as in classic ray tracers, unless asked to
// jitter it too (the viewer's refinement passes at 1 spp).
#pragma once

#include "math/Random.h"
#include "math/Vec.h"

namespace prism {

class PixelSampler {
 public:
  explicit PixelSampler(int samplesPerPixel, bool jitterSingleSample = false);

  int count() const { return count_; }
  int columns() const { return columns_; }
  int rows() const { return rows_; }

  // Offset in [0, 1)² of sample i; rng is the pixel's own stream, drawn in sample order.
  Vec2 offset(int i, Pcg32& rng) const;
  // Sample i's stratum: its centre in [0, 1)² and its size, in pixels.
  Vec2 stratumCentre(int i) const {
    return Vec2((static_cast<float>(i % columns_) + 0.5f) / static_cast<float>(columns_),
                (static_cast<float>(i / columns_) + 0.5f) / static_cast<float>(rows_));
  }
  Vec2 stratumSize() const {
    return Vec2(1.0f / static_cast<float>(columns_), 1.0f / static_cast<float>(rows_));
  }

 private:
  int count_;
  bool jitterSingle_;
  int columns_;
  int rows_;
};

}  // namespace prism
