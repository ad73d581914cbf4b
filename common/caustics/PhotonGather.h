// Caustic irradiance from a photon map by density estimation, in one of two ways:
//  - per-photon radii (classic photon mapping, and progressive passes without a fixed radius):
//    each photon spreads its power over a kernel whose radius is the distance to its own k-th
//    nearest photon (capped, and scaled by radiusScale in progressive passes). This is the
//    sample-point estimate: every kernel integrates to 1, so the estimate integrates to exactly
//    the photons' power. The balloon estimate it replaces — the k nearest photons *of the
//    shading point* — does not: beyond the edge of a lit region its disc reaches back into the
//    light, and its integral exceeded the flux by 2.6 % at k = 100 and 5 % at k = 400
//    (tests/common/caustics/PhotonGatherFlux_test.cpp).
//  - every photon within a fixed radius (one pass of progressive photon mapping, Knaus & Zwicker
//    2011, when the scene sets its radius).
// Photons that arrived from behind the surface (through a thin wall) are left out.
#pragma once

#include <memory>
#include <vector>

#include "caustics/CausticEstimator.h"
#include "caustics/PhotonDiscs.h"
#include "caustics/PhotonGatherSettings.h"
#include "caustics/PhotonMap.h"

namespace prism {

class PhotonGather : public CausticEstimator {
 public:
  // Per-photon radii are found here, on up to `threads` threads (0: all cores).
  PhotonGather(std::shared_ptr<const PhotonMap> map, const PhotonGatherSettings& settings,
               int threads = 0);
  // With the per-photon radii found already (photonRadii(), by photon index, before
  // radiusScale): by the ranks of a run together (master/frame/PhotonPass.h). The disc tree is
  // built on up to `threads` threads.
  PhotonGather(std::shared_ptr<const PhotonMap> map, const PhotonGatherSettings& settings,
               std::vector<float> radii, int threads = 0);
  // Whether a gather from `photons` photons with these settings needs each photon's radius.
  static bool needsRadii(const PhotonGatherSettings& settings, size_t photons) {
    return !settings.fixedRadius && photons > 0;
  }

  Color irradiance(const Vec3& position, const Vec3& normal) const override;
  // With the pixel's footprint: the pixel's average of the photons' kernels, so a focus narrower
  // than a pixel gives that pixel its average, not the value at one point of it. A photon
  // narrower than the footprint counts the share of its kernel the footprint holds, over the
  // footprint's area; one up to twice the pixel's reach, the mean of its kernel over the
  // footprint; a wider one keeps its kernel at the sample's point. With several samples a pixel,
  // each sample's share is its stratum's cell of the footprint, about the cell's centre
  // (PixelFootprint::sampleCell, offset): the cells tile the pixel.
  Color irradianceAt(const SurfaceHit& s, const PixelFootprint& footprint = {}) const override;
  bool usesFootprint() const override { return true; }

  const PhotonMap& map() const { return *map_; }
  const std::shared_ptr<const PhotonMap>& sharedMap() const { return map_; }
  const PhotonGatherSettings& settings() const { return settings_; }

 private:
  Color irradianceWithin(const Vec3& position, const Vec3& normal,
                         const PixelFootprint& footprint) const;

  std::shared_ptr<const PhotonMap> map_;
  PhotonGatherSettings settings_;
  std::unique_ptr<const PhotonDiscs> discs_;  // per-photon radii only
};

}  // namespace prism
