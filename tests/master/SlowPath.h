// The slow paths a cancellation test compares itself with, timed in the same test on the same
// machine: a sanitizer build or a loaded CI machine slows the slow path and the cancelled one
// alike, where a fixed bound in seconds fails on a slow machine and passes a broken
// cancellation on a fast one. Each projects the whole job's time from a share of it (1/fraction,
// about 100 ms of work), so the test pays a little for its yardstick.
#pragma once

#include <chrono>
#include <cstdint>

#include "caustics/PhotonMap.h"
#include "caustics/PhotonRadii.h"
#include "caustics/PhotonTracer.h"
#include "scene/Scene.h"

namespace prism::test {

template <typename Work>
double secondsOf(Work work) {
  const auto start = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Tracing `photons` photons of one pass of scene's lights on `threads` threads.
inline double projectedTraceSeconds(const Scene& scene, uint64_t photons, int threads,
                                    uint64_t fraction = 50) {
  const PhotonTracer tracer(scene, photons, scene.causticSettings().maxBounces);
  const uint64_t share = photons / fraction;
  return static_cast<double>(fraction) *
         secondsOf([&] { tracePhotons(tracer, 1, 0, share, threads); });
}

// Finding the k-NN radius of every photon of map on `threads` threads.
inline double projectedRadiiSeconds(const PhotonMap& map, int k, float maxRadius, int threads,
                                    uint64_t fraction = 20) {
  const size_t chunks = (map.size() / fraction + kPhotonRadiiChunk - 1) / kPhotonRadiiChunk;
  const size_t share = std::min(map.size(), std::max<size_t>(1, chunks) * kPhotonRadiiChunk);
  return static_cast<double>(map.size()) / static_cast<double>(share) *
         secondsOf([&] { photonRadiiShare(map, k, maxRadius, false, 0, share, threads); });
}

}  // namespace prism::test
