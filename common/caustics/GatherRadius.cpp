#include "caustics/GatherRadius.h"

#include <algorithm>
#include <cmath>

#include "caustics/AutomaticGather.h"

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

PhotonGatherSettings classicGather(const CausticSettings& c, float maxRadius) {
  if (c.automaticGather) {
    return {false, automaticGatherLargestK(c.gatherNoise), maxRadius, c.filter, 1.0f, true};
  }
  return {false, c.gather, maxRadius, c.filter, 1.0f, false};
}

PhotonGatherSettings progressiveGather(const CausticSettings& c, float maxRadius, int pass,
                                       const PhotonGatherSettings& previous) {
  if (c.radius > 0.0f) {
    const float radius =
        pass == 1 ? c.radius : nextProgressiveRadius(previous.radius, pass, c.alpha);
    return {true, c.gather, radius, c.filter, 1.0f};
  }
  PhotonGatherSettings gather = classicGather(c, maxRadius);
  gather.radiusScale =
      pass == 1 ? 1.0f : nextProgressiveRadius(previous.radiusScale, pass, c.alpha);
  return gather;
}

}  // namespace prism
