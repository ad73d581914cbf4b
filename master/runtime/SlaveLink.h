// Rank 0's line to its slaves, for the whole run: what it knows of every rank (the roster) and
// the one place that reads their messages. Every phase that listens to the slaves (tile
// frames, photon passes, the link probe, the wait for Ready) receives through it, so status
// messages mean the same everywhere: a Ready goes into the roster, an Error ends the run as
// std::runtime_error("rank k: text"), and any message at all shows its rank is alive.
//
// Liveness: a slave heartbeats every kHeartbeatSeconds once it has built its scene and said
// Ready. One silent for heartbeatTimeoutSeconds after that is retired (retireSilent), so a dead
// or frozen slave costs seconds, not a lease. Silence is counted only while rank 0 listens: after
// rank 0 has been busy elsewhere (building caustic maps, say), its slaves get a heartbeat's time
// to be heard before any is judged. A slave still building its scene is bounded by the lease
// (master/runtime/TileScheduler.h) instead. Coordinating thread only.
#pragma once

#include <optional>
#include <vector>

#include "cluster/DistributionOptions.h"
#include "render/RayCounters.h"
#include "transport/Transport.h"
#include "util/Stopwatch.h"
#include "wire/Messages.h"

namespace prism {

// What rank 0 knows of one rank, and what it did.
struct RankStats {
  int rank = 0;
  int threads = 0;            // render threads (a slave's from its Ready)
  size_t tiles = 0;           // tiles it delivered first
  RayCounters rays;           // of those tiles
  double busySeconds = 0.0;   // thread-seconds spent rendering them
  double buildSeconds = 0.0;  // building its Scene from the description
  // A slave's own start (from its Ready): process start to command (-1: not known), MPI_Init.
  double startSeconds = -1.0;
  double mpiInitSeconds = 0.0;
  size_t staleTiles = 0;  // results dropped: duplicates, or tiles of frames already ended
  size_t lostTiles = 0;   // tiles it received but lost (named by its heartbeat), re-issued
  bool retired = false;   // stopped answering, or known gone; its tiles were re-issued
};

// A message from a slave that is not only status (TileResult, Progress, PhotonShare, Echo,
// Shutdown), decoded to its envelope.
struct SlaveMessage {
  int source = 0;
  wire::Message message;
};

class SlaveLink {
 public:
  // cluster null (or of one rank): a run without slaves; every call is then trivial.
  SlaveLink(Transport* cluster, const DistributionOptions& options);

  Transport* transport() const { return cluster_; }
  int ranks() const { return static_cast<int>(ranks_.size()); }
  bool hasSlaves() const { return ranks() > 1; }
  const DistributionOptions& options() const { return options_; }

  const RankStats& rank(int r) const { return ranks_[static_cast<size_t>(r)]; }
  bool retired(int r) const { return rank(r).retired; }
  bool ready(int r) const { return ready_[static_cast<size_t>(r)]; }
  // Per rank: retired (master/runtime/SlaveShutdown.h waits less for those).
  std::vector<bool> retiredRanks() const;
  void retire(int r);

  // Sends to a live slave; a send the transport refuses retires it. False then, or when the
  // rank was retired already.
  bool send(int r, std::vector<uint8_t> bytes);

  // Waits up to timeoutSeconds for a message and returns it unless it was only status. Throws
  // std::runtime_error for a slave's Error, wire::WireError for a malformed message. Ends early,
  // with none, after wake().
  std::optional<SlaveMessage> receive(double timeoutSeconds);
  // Ends a receive() in progress, or the next one; safe from any thread.
  void wake() {
    if (cluster_) cluster_->wake();
  }

  // Retires the slaves that said Ready and have been silent past the heartbeat timeout;
  // returns the ones retired now. Call after receiving what has arrived.
  std::vector<int> retireSilent();

 private:
  void noteListening(SteadyClock::time_point now);

  Transport* cluster_;
  DistributionOptions options_;
  std::vector<RankStats> ranks_;
  std::vector<bool> ready_;
  std::vector<SteadyClock::time_point> lastHeard_;
  SteadyClock::time_point lastListened_;
};

}  // namespace prism
