// How a photon gather estimates density (see PhotonGather.h). Apart from the estimator so the
// wire format can carry it to the slaves with the photons.
#pragma once

#include "scene/SceneDescription.h"

namespace prism {

struct PhotonGatherSettings {
  // true: every photon within radius (a fixed-radius pass); false: each photon spread over its
  // own radius, the distance to its k-th nearest photon capped at radius, times radiusScale.
  bool fixedRadius = false;
  int k = 100;
  float radius = 0.1f;
  PhotonFilter filter = PhotonFilter::Cone;
  // Progressive passes with per-photon radii shrink them all by this factor (1: classic).
  float radiusScale = 1.0f;
  // Per-photon radii only: k chosen per photon up to k (caustics/AutomaticGather.h).
  bool automaticK = false;
};

}  // namespace prism
