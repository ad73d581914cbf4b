// Traces caustic photons: from each point light, only towards caustic casters (through its
// projection map), through specular reflection and refraction, and stores each one at the first
// receiving surface it meets after at least one specular bounce. Direct light is never stored;
// shadow rays compute it, and they are blocked by every object, transparent or not, so light
// that passes through a caster reaches receivers only as photons: nothing is counted twice or
// lost (see docs/caustics.md).
//
// At each specular surface Russian roulette picks reflection (probability = the mean of the
// reflect weights), refraction (the mean of the transmit weights) or absorption; the surviving
// photon's power is multiplied by weight / probability, so colourless glass and mirrors leave it
// unchanged and the estimate stays unbiased.
//
// Photon i of pass p leaves its light along Halton point (p · n + i − first) of that light (n its
// photons per pass), evenly spread like a jittered grid. Its first kStratifiedRoulette roulette
// decisions take the further coordinates of the same Halton point (bases 7, 11, 13, 17), so
// that among the photons through any small patch of a caster the share reflected, refracted
// and absorbed is the probabilities' and not a random draw of them: random thinning left
// noise of about 1/√k in every estimate. Later decisions come from the photon's own random
// stream keyed by (seed, i, p). The photons traced do not depend on how the index range is
// split between threads or ranks.
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "caustics/Photon.h"
#include "caustics/PhotonTraceStats.h"
#include "caustics/ProjectionMap.h"
#include "scene/Scene.h"

namespace prism {

// Roulette decisions along a photon's path that follow its Halton point (see above).
constexpr int kStratifiedRoulette = 4;

// One light's share of the photons of a pass.
struct PhotonLightPlan {
  size_t light = 0;  // index into Scene::lights()
  ProjectionMap map;
  uint64_t first = 0, count = 0;                  // photon indices [first, first + count)
  Color powerPerPhoton{0.0f};                     // W
  float emissionShift[3] = {0.0f, 0.0f, 0.0f};    // rotation of the light's Halton points
  float rouletteShift[kStratifiedRoulette] = {};  // rotation of their roulette coordinates
};

class PhotonTracer {
 public:
  // Plans the emission of `photons` photons per pass over the scene's lights, in proportion to
  // each light's flux towards the casters.
  PhotonTracer(const Scene& scene, uint64_t photons, int maxBounces);

  // False when no light can reach a caster: then there is nothing to trace.
  bool hasWork() const { return total_ > 0; }
  uint64_t photonsPerPass() const { return total_; }
  const std::vector<PhotonLightPlan>& plans() const { return plans_; }

  // Traces photons [first, first + count) of pass `pass`, appending the stored ones to out in
  // photon-index order.
  PhotonTraceStats trace(uint32_t pass, uint64_t first, uint64_t count,
                         std::vector<Photon>& out) const;

 private:
  void tracePhoton(uint32_t pass, uint64_t index, const PhotonLightPlan& plan,
                   std::vector<Photon>& out, PhotonTraceStats& stats) const;

  const Scene& scene_;
  int maxBounces_;
  uint64_t total_ = 0;
  std::vector<PhotonLightPlan> plans_;
};

// trace() over `threads` threads (0: every available core). The photons come back in index
// order whatever the thread count. Once *cancel is set, chunks not yet begun are skipped: the
// result is then incomplete and only good for dropping.
std::vector<Photon> tracePhotons(const PhotonTracer& tracer, uint32_t pass, uint64_t first,
                                 uint64_t count, int threads, PhotonTraceStats* stats = nullptr,
                                 const std::atomic<bool>* cancel = nullptr);

}  // namespace prism
