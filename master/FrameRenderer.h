// Renders one frame: plans tiles, hands them out through the TileScheduler to this process's
// render threads and, in an MPI run, to the slave ranks, and assembles the results. The
// single-process `prism render` runs exactly this code with no slaves.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "image/ImageRgb.h"
#include "master/TileScheduler.h"
#include "render/RayCounters.h"
#include "scene/Scene.h"

namespace prism {

class MpiSession;

struct FrameOptions {
  int threads = 0;   // render threads on this rank; 0: every available core
  int tileSize = 0;  // 0: automatic
  Schedule schedule = Schedule::Dynamic;
  double leaseSeconds = 30.0;  // a slave silent this long while holding tiles is retired
  int prefetch = 2;            // tiles in flight per slave, so none waits for its next job
  // Called on the coordinating thread with (tiles done, tiles total), about ten times a second.
  std::function<void(size_t, size_t)> progress;
};

// What one rank did for the frame.
struct WorkerStats {
  int rank = 0;
  int threads = 0;
  size_t tiles = 0;
  RayCounters rays;
  double busySeconds = 0.0;   // thread-seconds spent rendering its tiles
  double buildSeconds = 0.0;  // building its Scene from the description
  size_t duplicates = 0;      // results for tiles someone else had already delivered
  size_t lostTiles = 0;       // tiles it received but lost (found by its heartbeat), re-issued
  bool retired = false;       // stopped answering; its tiles were re-issued
};

struct FrameResult {
  ImageRgb image;
  RayCounters rays;
  size_t tileCount = 0;
  int tileSize = 0;
  int threads = 0;  // render threads on rank 0
  double seconds = 0.0;
  double busyThreadSeconds = 0.0;
  std::vector<WorkerStats> workers;  // index = rank
  size_t reissuedTiles = 0;
};

// Throws std::runtime_error when a slave reports an error (the message names the rank).
// With cluster == nullptr (or a single rank) everything is rendered here.
FrameResult renderFrame(const Scene& scene, const FrameOptions& options,
                        MpiSession* cluster = nullptr);

}  // namespace prism
