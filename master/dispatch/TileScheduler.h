// Which tile goes to which worker, and what happens when a worker goes quiet. Pure bookkeeping
// (time is passed in), so it is tested without MPI or threads.
//
// Dynamic schedule: one queue in row-major order; every worker takes the next tile.
// Static schedule: tile i belongs to worker i mod W (interleaved rows of tiles), for honest
// comparison with the dynamic one.
// Idle workers (`prism speedup` measures with some ranks left out) take part in neither
// schedule: they are never given a tile, and W counts only the active ones.
// Leases: a tile handed out is leased to its worker. A worker that holds leases and has
// delivered no tile for leaseSeconds (counted from its last delivered tile, or from its first
// lease after holding none) is retired: its tiles go back to the front of the queue for anyone
// to take, and it gets no more work. Heartbeats do not extend a lease: they prove a slave is
// alive (master/dispatch/SlaveLink.h retires a silent one within seconds), while the lease bounds a
// slave that answers but makes no progress. A late result from a retired worker is still
// accepted if the tile is not done yet; a second copy of a tile is reported as a duplicate.
// A live worker's heartbeat lists the tiles it holds; a tile it was sent, has received and
// neither holds nor delivered was lost, and goes back to the queue at once.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "cluster/DistributionOptions.h"

namespace prism {

class TileScheduler {
 public:
  // active[w] says whether worker w is given tiles; empty: every worker is. At least one must be.
  TileScheduler(size_t tileCount, int workerCount, Schedule schedule, double leaseSeconds,
                const std::vector<bool>& active = {});

  // A worker whose silence never retires it (the master's own threads).
  void exemptFromLeases(int worker);

  // The next tile for this worker, or nothing if none is available to it now.
  std::optional<uint32_t> next(int worker, double now);

  // Records a finished tile and that the worker is alive. Returns false for a duplicate, a
  // tile index out of range or a tile never handed out.
  bool complete(uint32_t tile, int worker, double now);

  // Re-queues the tiles among the first jobsReceived sent to this worker that it no longer
  // holds and has not delivered; returns how many.
  size_t reconcile(int worker, uint64_t jobsReceived, const std::vector<uint32_t>& heldTiles);

  // Retires workers past their lease and re-queues their tiles; returns them.
  std::vector<int> reclaimExpired(double now);
  // Retires a worker known to be gone (a send to it failed) and re-queues its tiles.
  void retire(int worker) {
    if (!workers_[worker].retired) retire(workers_[worker]);
  }

  bool finished() const { return doneCount_ == done_.size(); }
  size_t doneCount() const { return doneCount_; }
  size_t outstanding(int worker) const { return workers_[worker].leased.size(); }
  bool retired(int worker) const { return workers_[worker].retired; }
  bool idle(int worker) const { return workers_[worker].idle; }
  size_t reissuedCount() const { return reissued_; }

 private:
  struct Worker {
    std::deque<uint32_t> own;         // static schedule: this worker's tiles
    std::vector<uint32_t> leased;     // handed out, not finished
    std::vector<uint64_t> leasedSeq;  // the order in which each leased tile was sent
    uint64_t sent = 0;
    double lastProgress = 0.0;  // last tile delivered, or first lease after holding none
    bool exempt = false;
    bool retired = false;
    bool idle = false;  // not taking part in this frame
  };

  void retire(Worker& worker);

  Schedule schedule_;
  double leaseSeconds_;
  std::deque<uint32_t> shared_;  // dynamic queue, and reclaimed tiles in both schedules
  std::vector<Worker> workers_;
  std::vector<bool> done_;
  std::vector<bool> issued_;
  size_t doneCount_ = 0;
  size_t reissued_ = 0;
};

}  // namespace prism
