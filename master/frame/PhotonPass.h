// The photon half of a caustic pass in a run: rank 0 splits the pass's photon indices between
// itself and the live slaves (in proportion to their threads), traces its share while it
// collects theirs, and assembles every photon in index order, so the map is the same whatever
// the number of ranks. A slave that goes silent (master/dispatch/SlaveLink.h), or one still
// building its scene that stays silent for the lease time, is retired and rank 0 traces its share
// itself. The map then goes to every live slave with its gather settings, and where the gather
// needs each photon's radius the ranks find them together the same way: each a share of the map's
// spatial order, rank 0 a silent slave's, and rank 0 sends every radius to every slave.
#pragma once

#include <atomic>
#include <memory>
#include <optional>
#include <vector>

#include "caustics/PhotonGather.h"
#include "caustics/PhotonMap.h"
#include "caustics/PhotonTracer.h"
#include "master/dispatch/SlaveLink.h"
#include "master/dispatch/WorkDispatcher.h"

namespace prism {

// What a photon pass did: `prism render`'s run sums its passes, the viewer shows its last.
struct PhotonPassStats {
  PhotonTraceStats trace;
  double traceSeconds = 0.0;       // wall time until every share was in
  double buildSeconds = 0.0;       // kd-tree on rank 0
  double distributeSeconds = 0.0;  // sending the map to the slaves
  double radiiSeconds = 0.0;       // finding every photon's radius, and the gather's discs
  size_t mapBytes = 0;             // photons + kd-tree (summed passes: the largest map)
  size_t sentBytes = 0;
  std::vector<uint64_t> photonsByRank;  // photon indices each rank traced
  std::vector<uint64_t> radiiByRank;    // photons whose radius each rank found

  // Adds a later pass: counts, times and bytes sent summed, mapBytes the larger.
  PhotonPassStats& operator+=(const PhotonPassStats& later);
  double photonsPerSecond() const;  // emitted / traceSeconds
};

// One photon pass, the sequence `prism render`, the viewer and `prism speedup` all run: pass
// `pass`'s photons traced across the ranks (tracePhotonPass), then sent with their gather
// settings, each photon's radius found where the gather needs it, and rank 0's map and discs
// built (gatherFromPhotons). Returns rank 0's gather; null once *cancel is set.
std::shared_ptr<const PhotonGather> runPhotonPass(const PhotonTracer& tracer, uint32_t pass,
                                                  const PhotonGatherSettings& gather, int threads,
                                                  WorkDispatcher& dispatcher,
                                                  PhotonPassStats& stats, bool keep = false,
                                                  const std::atomic<bool>* cancel = nullptr);

// Traces pass `pass`: its photons in index order. threads: rank 0's tracing threads. Once
// *cancel is set (the viewer's camera moved; wake the link too), rank 0 stops tracing within a
// chunk of photons, tells the slaves still tracing their shares to stop (PhotonCancel: they send
// nothing for the pass) and returns none without waiting for them; a share already on its way
// arrives late and is ignored.
std::optional<std::vector<Photon>> tracePhotonPass(const PhotonTracer& tracer, uint32_t pass,
                                                   int threads, WorkDispatcher& dispatcher,
                                                   PhotonPassStats& stats,
                                                   const std::atomic<bool>* cancel = nullptr);

// Sends the photons of pass `pass` with their gather settings to every live slave, builds rank
// 0's photon map (the kd-tree) while the slaves build theirs, and returns rank 0's gather from
// it (its map: PhotonGather::sharedMap()). Per-photon radii are found by every live rank, a share
// each in proportion to its threads (rank 0's on `threads` threads, while it collects the others';
// a slave that goes silent has its share found here), and then sent to every slave, which gathers
// from that map once they arrive. The radii equal those one rank finds alone, bit for bit. keep:
// each slave keeps the map (with its radii) until the next map sent with keep, for
// sendPhotonMapAgain. Once *cancel is set (the viewer's camera moved), rank 0 stops its share
// within a chunk of photons, tells the slaves still finding theirs to stop (PhotonCancel) and
// returns null; a share already on its way arrives late and is ignored, and the slaves never
// gather from that map.
std::shared_ptr<const PhotonGather> gatherFromPhotons(std::vector<Photon> photons, uint32_t pass,
                                                      const PhotonGatherSettings& gather,
                                                      int threads, WorkDispatcher& dispatcher,
                                                      PhotonPassStats& stats, bool keep = false,
                                                      const std::atomic<bool>* cancel = nullptr);
// Tells every live slave that pass `pass` gathers from the map it keeps from pass `keptPass`.
void sendPhotonMapAgain(uint32_t pass, uint32_t keptPass, SlaveLink& link);

}  // namespace prism
