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
// Emission is stratified twice. Photons go round the light's c marked cells of the projection
// map in turn (sequence index s = p · n + i − first, n the light's photons per pass), so every
// cell gets its share to one photon over all the passes so far; the round visits cell (s mod c) · g
// mod c, g the integer coprime to c nearest c times the golden ratio's fraction, so that fewer
// photons than cells still spread over all of them, not over the first few. Within its cell, the
// photons of a pass are the first points of a (0, 2)-sequence (math/LowDiscrepancy.h), rotated by
// an offset of that cell's keyed by the seed and the pass: each progressive pass is a fresh
// stratified set, independent of the others (continuing one sequence across the passes made their
// errors alike: after 16 passes the focus read twice the error, docs/accuracy.md). The photons
// under any small patch of a caster then number its area's share to about one photon, where the
// Halton sequence over the whole map (its bases 3 and 5 spread a few hundred points per cell
// unevenly) left them nearly as uneven as random ones. The photon's first kStratifiedRoulette
// roulette decisions take further coordinates of its cell's sequence (Halton bases 3, 5, 7, 11,
// rotated the same way), so that among the photons through a small patch the share reflected,
// refracted and absorbed is the probabilities' and not a random draw of them. Later decisions come
// from the photon's own random stream keyed by (seed, i, p). The photons traced do not depend on
// how the index range is split between threads or ranks.
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "caustics/Photon.h"
#include "caustics/PhotonTraceStats.h"
#include "caustics/ProjectionMap.h"
#include "scene/Scene.h"

namespace prism {

// Roulette decisions along a photon's path that follow its cell's sequence (see above).
constexpr int kStratifiedRoulette = 4;

// One light's share of the photons of a pass.
struct PhotonLightPlan {
  size_t light = 0;  // index into Scene::lights()
  ProjectionMap map;
  uint64_t first = 0, count = 0;  // photon indices [first, first + count)
  Color powerPerPhoton{0.0f};     // W
  uint64_t cellStride = 1;  // g above: consecutive photons' cells lie this far apart in the list
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
