// The fraction of each side a viewer frame renders while the camera moves: full resolution, or
// a step of a ladder of reductions. Steps finer than 1/2 (3/4, 2/3) let a frame that just misses
// its time target keep most of its pixels instead of dropping to a quarter of them.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace prism {

struct FrameScale {
  int numerator = 1;
  int denominator = 1;

  bool full() const { return numerator >= denominator; }
  // A side of `fullSide` pixels at this scale, at least 1.
  int side(int fullSide) const {
    return std::max(1, static_cast<int>(int64_t{fullSide} * numerator / denominator));
  }
  double fraction() const { return static_cast<double>(numerator) / denominator; }
  // "1" or "2/3".
  std::string text() const {
    return full() ? "1" : std::to_string(numerator) + "/" + std::to_string(denominator);
  }
  friend bool operator==(const FrameScale& a, const FrameScale& b) {
    return int64_t{a.numerator} * b.denominator == int64_t{b.numerator} * a.denominator;
  }
};

// Full resolution, 3/4, 2/3, 1/2, then 1/3, 1/4, … down to 1/maxScale (finest first); 1/maxScale
// the coarsest. maxScale ≤ 1: full resolution only.
inline std::vector<FrameScale> frameScaleLadder(int maxScale) {
  std::vector<FrameScale> ladder{{1, 1}};
  if (maxScale < 2) return ladder;
  ladder.insert(ladder.end(), {{3, 4}, {2, 3}, {1, 2}});
  for (int d = 3; d <= maxScale; ++d) ladder.push_back({1, d});
  return ladder;
}

}  // namespace prism
