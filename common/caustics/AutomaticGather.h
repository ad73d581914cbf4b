// The automatic k of `gather: auto`: each photon's radius grows over k = 8, 16, 32, … up to the
// largest k the target noise asks for, while the photon densities those radii give stay
// consistent (the intersection of confidence intervals rule, ICI: Goldenshluger & Nemirovski
// 1997, Katkovnik 1999). Where the density is smooth a photon gets the largest k (the least
// noise); where its disc reaches a fold or a focus the estimates at growing k part, and it keeps
// the largest k before they did (less blur). docs/accuracy.md measures it against fixed k.
#pragma once

#include <functional>
#include <vector>

#include "caustics/PhotonMap.h"

namespace prism {

// The largest k for a target relative noise: a density estimate from k photons has a relative
// standard deviation of about 1/√k, so k = ⌈1/noise²⌉ (0.05 → 400, 0.1 → 100).
int automaticGatherLargestK(float noise);

// The squared radius chosen for one photon from its nearest photons (nearest first, itself
// included, as PhotonMap::nearest gives them for k = largestK within maxRadius²). Each k on the
// ladder gives the density k/(π r_k²) with a confidence interval of ±2/√k of it; the radius is
// the last r_k whose interval still meets all the smaller k's. Where fewer than k photons lie
// within maxRadius, the ladder ends there with maxRadius².
float automaticGatherRadius2(const std::vector<PhotonNeighbour>& nearestFirst, int largestK,
                             float maxRadius2);
// The ks the ladder tries, smallest first (8, 16, 32, … and largestK last).
std::vector<int> automaticGatherLadder(int largestK);
// The same from the found photons' count (at most the ladder's last k) and their squared
// distances by rank: distance2OfRank(k) is the k-th smallest, asked only for ladder ks up to found.
float automaticGatherRadius2(const std::vector<int>& ladder, int found,
                             const std::function<float(int)>& distance2OfRank, float maxRadius2);

}  // namespace prism
