// Caustic mapping behind the CausticEstimator interface: one CausticMap per point light whose
// light space holds a caster, built from the scene alone (so every rank builds the same maps
// and no map travels on the wire); the irradiance at a receiver is the sum over the lights.
#pragma once

#include <memory>
#include <vector>

#include "caustics/CausticEstimator.h"
#include "caustics/CausticMap.h"

namespace prism {

// The scene's caustic settings with the Gaussian blur kept or turned off (the viewer's `b`).
inline CausticSettings causticMapSettings(CausticSettings settings, bool blur) {
  if (!blur) settings.mapBlurRadius = 0;
  return settings;
}

class CausticMapEstimator : public CausticEstimator {
 public:
  // Builds the maps with `threads` threads (0: all cores), with the scene's caustic settings
  // or with `settings`.
  CausticMapEstimator(const Scene& scene, int threads)
      : CausticMapEstimator(scene, scene.causticSettings(), threads) {}
  CausticMapEstimator(const Scene& scene, const CausticSettings& settings, int threads);

  Color irradiance(const Vec3& position, const Vec3& normal) const override;
  // Map by map, every point's texels found before any is read (CausticMap::addIrradiance).
  void irradianceAtEach(const SurfaceHit* const* points, int count, Color* out) const override;

  bool empty() const { return maps_.empty(); }
  const std::vector<std::unique_ptr<CausticMap>>& maps() const { return maps_; }
  // Summed over the lights.
  CausticMapStats stats() const;

 private:
  std::vector<std::unique_ptr<CausticMap>> maps_;
};

}  // namespace prism
