// A discrete-event simulation of the master's tile queue (master/frame/FrameRenderer.cpp,
// master/dispatch/TileScheduler.h) for any number of workers, so `prism speedup` can project past
// the machine it measured on. It replays measured per-tile render times and a measured link:
//   - the master keeps `prefetch` tiles in flight per worker, refilling a worker when one of
//     its results arrives (dynamic: the next tile of one shared queue; static: the next of the
//     worker's own tiles, tile i going to worker i mod p), and fills the workers in rank order
//     at the start, as serviceSlaves does;
//   - a message takes `latency` plus its bytes over `bandwidth`; the master's link is shared, so
//     job sends leave it one after another and results reach it one after another;
//   - a worker renders its queued tiles on `threadsPerWorker` threads, each at `cpuShare` of a
//     core (below 1 when the measured machine ran more render threads than it has cores).
// The frame ends when the last result has reached the master. Deterministic: ties are broken by
// the order in which events were scheduled. Pure C++: no MPI, no threads, no clock.
#pragma once

#include <cstddef>
#include <limits>
#include <vector>

#include "master/dispatch/TileScheduler.h"

namespace prism {

struct LinkModel {
  double latencySeconds = 0.0;  // one way, per message
  double bytesPerSecond = std::numeric_limits<double>::infinity();
};

struct ScheduleSimulation {
  std::vector<double> tileSeconds;  // each tile's render time on one thread, in plan order
  std::vector<double> resultBytes;  // each tile's result message; empty: all 0
  double jobBytes = 0.0;            // one tile job message
  int workers = 1;
  int threadsPerWorker = 1;
  int prefetch = 2;
  Schedule schedule = Schedule::Dynamic;
  LinkModel link;
  double cpuShare = 1.0;
};

struct SimulatedFrame {
  double seconds = 0.0;             // from the first job sent to the last result received
  std::vector<double> busySeconds;  // per worker: thread-seconds rendering
  std::vector<size_t> tilesByWorker;
};

// Throws std::invalid_argument for no workers, threads or prefetch, a cpuShare outside (0, 1],
// or resultBytes of the wrong length.
SimulatedFrame simulateTileSchedule(const ScheduleSimulation& simulation);

}  // namespace prism
