// How a run spreads its work over ranks and threads: one struct, filled once from the command
// line and read by the master's dispatcher and by every slave.
#pragma once

#include "cluster/FaultInjection.h"

namespace prism {

// Dynamic: one pull queue in row-major order. Static: tile i belongs to worker i mod W, for
// honest comparison with the dynamic one (master/dispatch/TileScheduler.h).
enum class Schedule { Dynamic, Static };

struct DistributionOptions {
  int threads = 0;   // render threads on each rank; 0: every core available to the rank
  int tileSize = 0;  // tile edge in pixels; 0: automatic
  Schedule schedule = Schedule::Dynamic;
  int prefetch = 2;  // tiles in flight per slave render thread, so none waits for its next job
  // A slave that has said Ready and is then silent this long (it heartbeats every
  // kHeartbeatSeconds) is retired and its tiles re-issued: a dead or frozen slave costs seconds.
  double heartbeatTimeoutSeconds = 2.0;
  // A slave that answers but delivers no tile for this long while holding tiles is retired
  // too (and a slave still building its scene is given this long).
  double leaseSeconds = 30.0;
  double masterTimeoutSeconds = 600.0;  // a slave gives up when rank 0 is silent this long
  FaultInjection fault;                 // testing only: one slave misbehaves
};

// How often a slave tells rank 0 it is alive and which tiles it holds.
inline constexpr double kHeartbeatSeconds = 0.5;

}  // namespace prism
