// The photon half of a caustic pass in a run: rank 0 splits the pass's photon indices between
// itself and the live slaves (in proportion to their threads), traces its share while it
// collects theirs, and assembles every photon in index order, so the map is the same whatever
// the number of ranks. A slave that goes silent (master/SlaveLink.h), or one still building its
// scene that stays silent for the lease time, is retired and rank 0 traces its share itself. The
// map then goes to every live slave with its gather settings.
#pragma once

#include <atomic>
#include <memory>
#include <vector>

#include "caustics/PhotonGather.h"
#include "caustics/PhotonMap.h"
#include "caustics/PhotonTracer.h"
#include "master/SlaveLink.h"

namespace prism {

struct PhotonPassStats {
  PhotonTraceStats trace;
  double traceSeconds = 0.0;       // wall time until every share was in
  double buildSeconds = 0.0;       // kd-tree on rank 0
  double distributeSeconds = 0.0;  // sending the map to the slaves
  size_t mapBytes = 0;
  size_t sentBytes = 0;
  std::vector<uint64_t> photonsByRank;  // photon indices each rank traced
};

// Traces pass `pass` and builds rank 0's photon map. threads: rank 0's tracing threads. Once
// *cancel is set (the viewer's camera moved; wake the link too), rank 0 stops tracing within a
// chunk of photons, tells the slaves still tracing their shares to stop (PhotonCancel: they send
// nothing for the pass) and returns null without waiting for them; a share already on its way
// arrives late and is ignored.
std::shared_ptr<const PhotonMap> tracePhotonPass(const PhotonTracer& tracer, uint32_t pass,
                                                 int threads, SlaveLink& link,
                                                 PhotonPassStats& stats,
                                                 const std::atomic<bool>* cancel = nullptr);

// Sends the map of pass `pass` with its gather settings to every live slave. keep: each keeps it
// (with its radii) until the next map sent with keep, for sendPhotonMapAgain.
void sendPhotonMap(const PhotonMap& map, uint32_t pass, const PhotonGatherSettings& gather,
                   SlaveLink& link, PhotonPassStats& stats, bool keep = false);
// Tells every live slave that pass `pass` gathers from the map it keeps from pass `keptPass`.
void sendPhotonMapAgain(uint32_t pass, uint32_t keptPass, SlaveLink& link);

}  // namespace prism
