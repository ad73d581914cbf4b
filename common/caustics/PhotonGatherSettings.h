// How a photon gather estimates density (see PhotonGather.h). Apart from the estimator so the
// wire format can carry it to the slaves with the photons.
#pragma once

#include "scene/SceneDescription.h"

namespace prism {

struct PhotonGatherSettings {
  bool fixedRadius = false;  // true: every photon within radius; false: k nearest within it
  int k = 100;
  float radius = 0.1f;
  PhotonFilter filter = PhotonFilter::Cone;
};

}  // namespace prism
