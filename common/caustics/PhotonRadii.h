// Each photon's own gather radius: the distance to its k-th nearest photon, found by one range
// search per photon, bounded by the radii of the photons placed just before it, and a selection
// among the distances it returns (no sorted insert of each candidate, which cost most at k = 400).
// Photons are placed in chunks of the tree's spatial order, each chunk on its own, so the ranks of
// a run can find the radii of a share each (master/frame/PhotonPass.h) and get every radius as
// one rank finding them all would.
#pragma once

#include <atomic>
#include <cstddef>
#include <vector>

#include "caustics/PhotonMap.h"

namespace prism {

// Photons placed one after another by one thread, in the tree's spatial order: each bounds the
// next. A share of the radii starts at a multiple of it.
inline constexpr size_t kPhotonRadiiChunk = 64;

// Each photon's radius: the distance to its k-th nearest photon (itself included), capped at
// maxRadius; with automaticK, each photon's own k, at most k (caustics/AutomaticGather.h).
// The same on every rank and for any thread count: each photon's answer depends on the map alone,
// and equals what PhotonMap::nearest gives it.
std::vector<float> photonRadii(const PhotonMap& map, int k, float maxRadius, bool automaticK,
                               int threads = 0);

// The radii of the photons at positions [first, first + count) of map.spatialOrder(), in that
// order: a share of photonRadii()'s answer (first a multiple of kPhotonRadiiChunk). Once *cancel
// is set the chunks not yet started are left at 0.
std::vector<float> photonRadiiShare(const PhotonMap& map, int k, float maxRadius, bool automaticK,
                                    size_t first, size_t count, int threads = 0,
                                    const std::atomic<bool>* cancel = nullptr);

// Puts a share's radii (found for positions first, first + 1, ... of map.spatialOrder()) at their
// photons' indices in radii (map.size() long).
void placePhotonRadii(const PhotonMap& map, size_t first, const std::vector<float>& share,
                      std::vector<float>& radii);

}  // namespace prism
