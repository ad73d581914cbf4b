// Rank 0's line to its slaves, for the whole run, and the one place that reads their messages:
// at the start, each set-up step's roll call (firstOfEachSlave: their Hellos before the scene is
// broadcast, their SceneAccepted before any rank builds); while the job runs, receive(), which
// every phase that listens to the slaves (tile frames, photon passes, the link probe, the wait
// for Ready) goes through; at the end, the slaves' Shutdown acknowledgements
// (nextShutdownAcknowledgement). Each message is checked against the message list
// (wire/Messages.h): one that only rank 0 sends, or one of another phase during a roll call, ends
// the run naming its rank. While the job runs, it also keeps what rank 0 knows of every rank
// (the roster, the run's one record of each rank: its facts from Ready, whether it is retired,
// and what it delivered), so status messages mean the same everywhere: a Ready goes into the
// roster, an Error ends the run as std::runtime_error("rank k: text"), and any message at all
// shows its rank is alive.
//
// Liveness: a slave heartbeats every kHeartbeatSeconds once it has built its scene and said
// Ready. One silent for heartbeatTimeoutSeconds after that is retired (retireSilent), so a dead
// or frozen slave costs seconds, not a lease. Silence is counted only while rank 0 listens: after
// rank 0 has been busy elsewhere (building caustic maps, say), its slaves get a heartbeat's time
// to be heard before any is judged. A slave still building its scene is bounded by the lease
// (master/dispatch/TileScheduler.h) instead. Sending and receiving: the coordinating thread only;
// the roster may be read and counted into from any thread (rank 0's render threads count the
// tiles they deliver).
#pragma once

#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "cluster/DistributionOptions.h"
#include "render/RayCounters.h"
#include "render/Tile.h"
#include "transport/Transport.h"
#include "util/Stopwatch.h"
#include "wire/Messages.h"

namespace prism {

// A set-up step's roll call: the first message of each slave (index: rank; rank 0's entry is left
// default), each of T's type, decoded. Waits up to timeoutSeconds in all. Throws
// std::runtime_error "rank k: text" for a slave's Error, "rank k sent Ready before Hello" for
// another type, and "rank k " + silence for a slave not heard in time. Instantiated for every
// message of the list; T must be one a slave sends in set-up.
template <class T>
std::vector<T> firstOfEachSlave(Transport& cluster, double timeoutSeconds,
                                const std::string& silence);

// The end of the run: the rank of the next slave to acknowledge it (its Shutdown), waiting up to
// waitSeconds; anything else a slave sends meanwhile is dropped.
std::optional<int> nextShutdownAcknowledgement(Transport& cluster, double waitSeconds);

// What rank 0 knows of one rank, and what it did: facts (who it is, how it started, whether it
// is retired) and counts (what it delivered). Counts add up over frames and subtract between two
// readings of the roster; forEachCount lists them once for both.
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

  // visit(mine, theirs) for each count of this record and of `other`.
  template <class Visit>
  void forEachCount(const RankStats& other, Visit&& visit) {
    visit(tiles, other.tiles);
    visit(rays, other.rays);
    visit(busySeconds, other.busySeconds);
    visit(staleTiles, other.staleTiles);
    visit(lostTiles, other.lostTiles);
  }
  // Adds a later record of the same rank (a later frame's): its counts are added, and its facts
  // replace these where it knows them (a rank retired in either stays retired).
  RankStats& operator+=(const RankStats& later) {
    forEachCount(later, [](auto& mine, const auto& theirs) { mine += theirs; });
    if (later.threads > 0) threads = later.threads;
    if (later.buildSeconds > 0.0) buildSeconds = later.buildSeconds;
    if (later.startSeconds >= 0.0) startSeconds = later.startSeconds;
    if (later.mpiInitSeconds > 0.0) mpiInitSeconds = later.mpiInitSeconds;
    retired = retired || later.retired;
    return *this;
  }
  // What was counted since `earlier`, a reading of the same rank's record; the facts are this
  // record's, the later.
  RankStats& operator-=(const RankStats& earlier) {
    forEachCount(earlier, [](auto& mine, const auto& theirs) { mine -= theirs; });
    return *this;
  }
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
  int ranks() const { return rankCount_; }
  bool hasSlaves() const { return ranks() > 1; }

  // The roster: one rank's record, or every rank's, as they are now.
  RankStats rank(int r) const;
  std::vector<RankStats> roster() const;
  bool retired(int r) const;
  bool ready(int r) const;
  // Per rank: retired (master/dispatch/SlaveShutdown.h waits less for those).
  std::vector<bool> retiredRanks() const;
  void retire(int r);
  // Rank 0's render threads, once they run.
  void setLocalThreads(int threads);
  // What a rank delivered: a tile accepted (the first copy), a result dropped (late, duplicate,
  // or of an ended frame), tiles it lost (named by its heartbeat, re-issued).
  void countDelivered(int r, const TileResult& tile);
  void countStale(int r);
  void countLost(int r, size_t tiles);

  // Sends to a live slave; a send the transport refuses retires it. False then, or when the
  // rank was retired already.
  bool send(int r, std::vector<uint8_t> bytes);

  // Waits up to timeoutSeconds for a message and returns it unless it was only status. Throws
  // std::runtime_error for a slave's Error, wire::WireError for a malformed message. Ends early,
  // with none, after wake().
  std::optional<SlaveMessage> receive(double timeoutSeconds);
  // Receives until the Echo of `sequence` comes back from rank `r` (a link probe's round trip),
  // handling what else arrives meanwhile as receive() does; false after timeoutSeconds.
  bool awaitEcho(int r, uint32_t sequence, double timeoutSeconds);
  // Ends a receive() in progress, or the next one; safe from any thread.
  void wake() {
    if (cluster_) cluster_->wake();
  }

  // Retires the slaves that said Ready and have been silent past the heartbeat timeout;
  // returns the ones retired now. Call after receiving what has arrived.
  std::vector<int> retireSilent();

 private:
  void noteListening(SteadyClock::time_point now);
  RankStats& recordLocked(int r) { return ranks_[static_cast<size_t>(r)]; }

  Transport* cluster_;
  DistributionOptions options_;
  int rankCount_ = 1;
  mutable std::mutex rosterMutex_;  // guards ranks_ and ready_
  std::vector<RankStats> ranks_;
  std::vector<bool> ready_;
  // The coordinating thread's alone:
  std::vector<SteadyClock::time_point> lastHeard_;
  SteadyClock::time_point lastListened_;
};

}  // namespace prism
