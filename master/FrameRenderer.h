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
#include "render/RenderPass.h"
#include "render/Tile.h"
#include "scene/Scene.h"

namespace prism {

class MpiSession;

// What the master knows about the ranks between the frames and photon passes of one run (index =
// rank): slaves that stopped answering stay retired, and what their Ready said is kept.
struct ClusterRoster {
  explicit ClusterRoster(int ranks = 1)
      : threads(static_cast<size_t>(ranks), 0),
        buildSeconds(static_cast<size_t>(ranks), 0.0),
        retired(static_cast<size_t>(ranks), false) {}
  // A slave's Ready (it may arrive during any phase that listens to the slaves).
  void recordReady(int rank, int rankThreads, double rankBuildSeconds) {
    threads[static_cast<size_t>(rank)] = rankThreads;
    buildSeconds[static_cast<size_t>(rank)] = rankBuildSeconds;
  }
  std::vector<int> threads;
  std::vector<double> buildSeconds;
  std::vector<bool> retired;
};

namespace wire {
struct Message;
}

// What every phase that listens to the slaves does with their status: a Ready goes into the
// roster, an Error becomes std::runtime_error("rank k: text"). False for any other message,
// which the caller handles.
bool handleSlaveStatus(const wire::Message& message, int source, ClusterRoster& roster);

struct FrameOptions {
  int threads = 0;   // render threads on this rank; 0: every available core
  int tileSize = 0;  // 0: automatic
  Schedule schedule = Schedule::Dynamic;
  double leaseSeconds = 30.0;  // a slave silent this long while holding tiles is retired
  int prefetch = 2;            // tiles in flight per slave, so none waits for its next job
  // Called on the coordinating thread with (tiles done, tiles total), about ten times a second.
  std::function<void(size_t, size_t)> progress;
  // The pass every tile renders; null: one pass of direct light. In an MPI run a pass with
  // caustics needs its photon map already sent to the slaves (master/PhotonPass.h).
  std::shared_ptr<const RenderPass> pass;
  ClusterRoster* roster = nullptr;  // read before the frame and updated after it, when given
  // `prism speedup` measures with part of the cluster: rank 0's threads may render nothing, and
  // only slaves 1..activeSlaves get tiles (-1: every slave); the others stay idle.
  bool masterRenders = true;
  int activeSlaves = -1;
  // Tags the frame's messages; every frame of a run needs its own, so that a late tile or
  // heartbeat from an earlier frame is recognised and ignored.
  uint32_t frameId = 0;
  // Polled by the coordinating loop; once true the frame stops: no more tiles are handed out,
  // the tiles being rendered here are abandoned and the result is marked interrupted.
  std::function<bool()> stopRequested;
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
  std::vector<TileRect> tiles;       // the frame's tiles, in plan order
  std::vector<double> tileSeconds;   // index = tile: the time its render thread spent on it
  size_t reissuedTiles = 0;
  bool interrupted = false;    // stopped by FrameOptions::stopRequested
  std::vector<bool> tileDone;  // index = tile: in the image (all, unless interrupted)
  size_t tilesDone() const;
};

// Throws std::runtime_error when a slave reports an error (the message names the rank).
// With cluster == nullptr (or a single rank) everything is rendered here.
FrameResult renderFrame(const Scene& scene, const FrameOptions& options,
                        MpiSession* cluster = nullptr);

}  // namespace prism
