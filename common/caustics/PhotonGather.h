// Caustic irradiance from a photon map by density estimation: either the k nearest photons
// within a maximum radius (classic photon mapping, Jensen 1996), or every photon within a fixed
// radius (one pass of progressive photon mapping). Photons that arrived from behind the surface
// (through a thin wall) are left out.
#pragma once

#include <memory>

#include "caustics/CausticEstimator.h"
#include "caustics/PhotonGatherSettings.h"
#include "caustics/PhotonMap.h"

namespace prism {

class PhotonGather : public CausticEstimator {
 public:
  PhotonGather(std::shared_ptr<const PhotonMap> map, const PhotonGatherSettings& settings)
      : map_(std::move(map)), settings_(settings) {}

  Color irradiance(const Vec3& position, const Vec3& normal) const override;

  const PhotonMap& map() const { return *map_; }
  const PhotonGatherSettings& settings() const { return settings_; }

 private:
  std::shared_ptr<const PhotonMap> map_;
  PhotonGatherSettings settings_;
};

}  // namespace prism
