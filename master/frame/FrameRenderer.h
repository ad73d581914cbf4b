// Renders one frame on the work dispatcher (master/dispatch/WorkDispatcher.h): plans the tiles,
// hands them to this process's render threads and, in an MPI run, to the slaves, and assembles the
// results. The single-process `prism render` runs exactly this code with no slaves.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cluster/DistributionOptions.h"
#include "image/ImageRgb.h"
#include "master/dispatch/SlaveLink.h"
#include "master/dispatch/WorkDispatcher.h"
#include "render/RayCounters.h"
#include "render/RenderPass.h"
#include "render/Tile.h"
#include "scene/Scene.h"
#include "util/Stopwatch.h"

namespace prism {

struct FrameOptions {
  DistributionOptions distribution;
  // Called on the coordinating thread with (tiles done, tiles total), about ten times a second.
  std::function<void(size_t, size_t)> progress;
  // The pass every tile renders; null: one pass of direct light. In an MPI run a pass with
  // caustics needs its photon map already sent to the slaves (master/frame/PhotonPass.h).
  std::shared_ptr<const RenderPass> pass;
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
  // When the run began as its user reads it (the command's start), from which a progressive
  // run's time budget counts (master/frame/PassBudget.h); unset: when its passes begin.
  std::optional<SteadyClock::time_point> runStart;
};

struct FrameResult {
  ImageRgb image;
  RayCounters rays;
  size_t tileCount = 0;
  int tileSize = 0;
  int threads = 0;  // render threads on rank 0
  double seconds = 0.0;
  // When the first tile of the run's first frame was accepted (none: no tile was).
  std::optional<SteadyClock::time_point> firstTileAt;
  double busyThreadSeconds = 0.0;
  std::vector<RankStats> workers;   // index = rank
  std::vector<TileRect> tiles;      // the frame's tiles, in plan order
  std::vector<double> tileSeconds;  // index = tile: the time its render thread spent on it
  size_t reissuedTiles = 0;
  bool interrupted = false;    // stopped by FrameOptions::stopRequested
  std::vector<bool> tileDone;  // index = tile: in the image (all, unless interrupted)
  size_t tilesDone() const;
};

// On the run's dispatcher (and its rank 0 threads, started on the first frame that renders on
// rank 0). Throws std::runtime_error when a slave reports an error (the message names the
// rank). FrameResult::workers holds what each rank did for this frame.
FrameResult renderFrame(WorkDispatcher& dispatcher, const FrameOptions& options);
// On this process alone, with a dispatcher of its own.
FrameResult renderFrame(const Scene& scene, const FrameOptions& options);

}  // namespace prism
