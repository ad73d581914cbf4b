// Renders tiles on a fixed number of threads. Each thread asks a job source for its next tile
// (the source blocks until one is available, and returns nothing when the work is over) and
// hands every finished tile to a result handler. On the master the source is the tile
// scheduler; on a slave it is the queue of jobs received from the master. Plain std::threads:
// the scheduling lives in the source, and the calling thread stays free for MPI and progress.
#pragma once

#include <atomic>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "cluster/TileJob.h"
#include "render/Tile.h"
#include "scene/Scene.h"
#include "util/ThreadCount.h"

namespace prism {

class TileWorkerPool {
 public:
  using JobSource = std::function<std::optional<TileJob>()>;
  using ResultHandler = std::function<void(TileResult&&)>;
  // Also told which job the result answers (its frame, its view).
  using JobResultHandler = std::function<void(const TileJob&, TileResult&&)>;

  TileWorkerPool(const Scene& scene, ThreadCount threads);
  ~TileWorkerPool();  // joins

  int threadCount() const { return threadCount_; }

  // Starts the threads. The source and handler are called concurrently from them.
  void start(JobSource source, ResultHandler onResult);
  void start(JobSource source, JobResultHandler onResult);
  bool started() const { return !threads_.empty(); }
  // Pools whose threads this process has started, ever: a run that means to keep one pool for
  // all its frames is tested with it.
  static uint64_t startedInProcess();
  // Waits for every thread to finish (each stops when the source returns nothing), then
  // rethrows the first exception a thread hit, if any.
  void join();
  // Whether a thread has stopped on an exception (join() will rethrow it).
  bool failed();
  // Abandons the tiles being rendered (each after its current row; no result is handed on), so
  // an interrupted run stops within a row's time rather than a tile's. A job whose frame has
  // ended (TileJob::frameEnded) is abandoned the same way, and the thread takes the next.
  void cancel() { cancelled_ = true; }

 private:
  const Scene& scene_;
  int threadCount_;
  std::vector<std::thread> threads_;
  std::mutex failureMutex_;
  std::exception_ptr failure_;
  std::atomic<bool> cancelled_{false};
};

}  // namespace prism
