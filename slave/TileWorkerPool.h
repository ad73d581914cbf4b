// Renders tiles on a fixed number of threads. Threads pull the next tile from a shared counter
// (a dynamic schedule), so fast and slow tiles balance out; results are handed to the caller as
// each tile finishes. Used by a rank for the tiles it is given (all of them in a single-process
// run). Threads are plain std::threads: pulling from an atomic counter is all the scheduling a
// rank needs, and it keeps the calling thread free to draw progress.
#pragma once

#include <atomic>
#include <functional>
#include <vector>

#include "render/Tile.h"
#include "scene/Scene.h"

namespace prism {

struct TileJob {
  uint32_t tileIndex = 0;
  TileRect rect;
};

class TileWorkerPool {
 public:
  using ResultHandler = std::function<void(TileResult&&)>;

  TileWorkerPool(const Scene& scene, int threadCount);

  int threadCount() const { return threadCount_; }

  // Renders every job and returns when all are done. onResult is called once per tile, from
  // the worker threads but never concurrently. onIdle, if given, runs on the calling thread
  // about every pollMilliseconds while the workers run (progress display).
  void renderAll(const std::vector<TileJob>& jobs, const ResultHandler& onResult,
                 const std::function<void()>& onIdle = {}, int pollMilliseconds = 100) const;

 private:
  const Scene& scene_;
  int threadCount_;
};

// Threads to use when the user asks for 0 ("all"): the cores this process may run on.
int availableCores();

}  // namespace prism
