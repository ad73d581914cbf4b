// Each photon's own gather radius: the distance to its k-th nearest photon, found by one range
// search per photon, bounded by the radii of the photons placed just before it, and a selection
// among the distances it returns (no sorted insert of each candidate, which cost most at k = 400).
#pragma once

#include <vector>

#include "caustics/PhotonMap.h"

namespace prism {

// Each photon's radius: the distance to its k-th nearest photon (itself included), capped at
// maxRadius; with automaticK, each photon's own k, at most k (caustics/AutomaticGather.h).
// The same on every rank and for any thread count: each photon's answer depends on the map alone,
// and equals what PhotonMap::nearest gives it.
std::vector<float> photonRadii(const PhotonMap& map, int k, float maxRadius, bool automaticK,
                               int threads = 0);

}  // namespace prism
