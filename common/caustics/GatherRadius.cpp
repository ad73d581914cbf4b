#include "caustics/GatherRadius.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "math/Random.h"

namespace prism {

float automaticMaxRadius(const Scene& scene) {
  float largest = 0.0f;
  for (const CasterBounds& c : scene.causticCasters()) {
    if (!c.plane) largest = std::max(largest, c.radius);
  }
  if (largest > 0.0f) return 0.1f * largest;
  const Aabb& b = scene.bounds();
  const float size = b.empty() ? 0.0f : glm::length(b.extent());
  return size > 0.0f ? 0.01f * size : 0.01f;
}

float nextProgressiveRadius(float previous, int pass, float alpha) {
  // r²(i) = r²(i−1)·(i − 1 + α)/i
  return previous * std::sqrt((static_cast<float>(pass - 1) + alpha) / static_cast<float>(pass));
}

float automaticProgressiveRadius(const PhotonMap& map, int k, float maxRadius) {
  constexpr size_t kProbes = 256;
  const size_t n = map.size();
  if (n == 0) return maxRadius;
  std::vector<PhotonNeighbour> neighbours;
  double sum = 0.0;
  size_t probes = 0;
  for (size_t i = 0; i < std::min(n, kProbes); ++i) {
    // Hashed, not evenly strided, indices: photon order follows the Halton emission sequence,
    // and a regular stride through it would probe a structured, unrepresentative subset.
    const Photon& p = map.photons()[mix64(i + 1) % n];
    sum += std::sqrt(map.nearest(p.position, k, maxRadius * maxRadius, neighbours));
    ++probes;
  }
  return static_cast<float>(sum / static_cast<double>(probes));
}

}  // namespace prism
