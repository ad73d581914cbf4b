// What a photon trace did with its photons. Plain counters, apart from the tracer, so the wire
// format (wire/Messages.h) can carry them without depending on the scene's BVH.
#pragma once

#include <cstdint>

namespace prism {

struct PhotonTraceStats {
  uint64_t emitted = 0;
  uint64_t stored = 0;  // photon records written (a photon may land on several receivers)
  // Every emitted photon ends as one of these two: emitted == missed + absorbed.
  uint64_t missed = 0;    // met no caster first (left the scene, or hit a non-caster)
  uint64_t absorbed = 0;  // reached a caster, then ended: stored on a receiver that does not
                          // cast, absorbed by roulette, escaped, or out of bounces
  PhotonTraceStats& operator+=(const PhotonTraceStats& o) {
    emitted += o.emitted;
    stored += o.stored;
    missed += o.missed;
    absorbed += o.absorbed;
    return *this;
  }
};

}  // namespace prism
