#include "caustics/AutomaticGather.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace prism {

namespace {
constexpr int kSmallestK = 8;
// Half-width of each confidence interval in standard deviations: 2 is the usual ICI choice
// (≈ 95 %). 1.5 measured noisier on the glass ball's smooth parts and no better at the ring's
// fold; so did Lepski's rule with the spread of nested estimates' differences at 2 (at 3 it
// measured as this one; docs/accuracy.md).
constexpr float kConfidence = 2.0f;
}  // namespace

int automaticGatherLargestK(float noise) {
  // Less a millionth: a float noise of 1/√k may square to a hair above 1/k.
  return static_cast<int>(std::ceil(1.0 / (static_cast<double>(noise) * noise) * (1.0 - 1e-6)));
}

float automaticGatherRadius2(const std::vector<PhotonNeighbour>& nearestFirst, int largestK,
                             float maxRadius2) {
  return automaticGatherRadius2(
      automaticGatherLadder(largestK), static_cast<int>(nearestFirst.size()),
      [&](int k) { return nearestFirst[static_cast<size_t>(k) - 1].distance2; }, maxRadius2);
}

float automaticGatherRadius2(const std::vector<int>& ladder, int found,
                             const std::function<float(int)>& distance2OfRank, float maxRadius2) {
  float lowest = 0.0f, highest = std::numeric_limits<float>::max(), chosen = maxRadius2;
  for (int k : ladder) {
    const bool complete = k <= found;  // else: the photons within maxRadius are all there is
    const int count = complete ? k : found;
    const float radius2 = complete ? distance2OfRank(k) : maxRadius2;
    if (count > 0 && radius2 > 0.0f) {
      const float density = count / radius2;  // π left out: only ratios matter
      const float half = kConfidence * density / std::sqrt(static_cast<float>(count));
      lowest = std::max(lowest, density - half);
      highest = std::min(highest, density + half);
      if (lowest > highest) break;
    }
    chosen = radius2;
    if (!complete) break;
  }
  return chosen;
}

std::vector<int> automaticGatherLadder(int largestK) {
  std::vector<int> ladder;
  for (int k = std::min(kSmallestK, largestK);; k = std::min(2 * k, largestK)) {
    ladder.push_back(k);
    if (k >= largestK) return ladder;
  }
}

}  // namespace prism
