#include "master/FrameRenderer.h"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <mutex>

#include "master/Framebuffer.h"
#include "master/TileJobWire.h"
#include "master/TilePlan.h"
#include "slave/TileWorkerPool.h"
#include "transport/MpiSession.h"
#include "wire/Messages.h"

namespace prism {
namespace {

using Clock = std::chrono::steady_clock;

constexpr int kLocalWorker = 0;  // rank 0's own render threads

// Everything the render threads and the coordinating thread share, behind one mutex.
class FrameState {
 public:
  FrameState(const std::vector<TileRect>& rects, int workers, const FrameOptions& options,
             int width, int height)
      : rects_(rects),
        pass_(options.pass),
        frameId_(options.frameId),
        scheduler_(rects.size(), workers, options.schedule, options.leaseSeconds,
                   activeWorkers(workers, options)),
        framebuffer_(width, height, rects.size()),
        stats_(static_cast<size_t>(workers)),
        tileSeconds_(rects.size(), 0.0),
        start_(Clock::now()) {
    scheduler_.exemptFromLeases(kLocalWorker);
    for (int r = 0; r < workers; ++r) stats_[r].rank = r;
    if (const ClusterRoster* roster = options.roster) {
      for (int r = 1; r < workers && static_cast<size_t>(r) < roster->retired.size(); ++r) {
        stats_[r].threads = roster->threads[r];
        stats_[r].buildSeconds = roster->buildSeconds[r];
        if (roster->retired[r]) {
          scheduler_.retire(r);
          stats_[r].retired = true;
        }
      }
    }
  }

  double now() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

  // Blocks until a tile is available to rank 0's threads, or returns nothing when the frame is
  // complete or abandoned. Tiles can reappear later (reclaimed leases), hence the wait.
  std::optional<TileJob> nextLocalJob() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      if (framebuffer_.complete() || abandoned_) return std::nullopt;
      if (const auto tile = scheduler_.next(kLocalWorker, now()))
        return TileJob(*tile, rects_[*tile], frameId_, nullptr, pass_);
      changed_.wait_for(lock, std::chrono::milliseconds(50));
    }
  }

  std::optional<TileJob> nextJobFor(int rank) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (const auto tile = scheduler_.next(rank, now())) {
      return TileJob(*tile, rects_[*tile], frameId_, nullptr, pass_);
    }
    return std::nullopt;
  }

  // Accepts a finished tile from a rank; malformed or duplicate results change nothing.
  void accept(const TileResult& tile, int rank) {
    const std::lock_guard<std::mutex> lock(mutex_);
    const bool planned =
        tile.tileIndex < rects_.size() && sameRect(tile.rect, rects_[tile.tileIndex]);
    if (planned && scheduler_.complete(tile.tileIndex, rank, now()) && framebuffer_.insert(tile)) {
      tileSeconds_[tile.tileIndex] = tile.seconds;
      WorkerStats& s = stats_[rank];
      ++s.tiles;
      s.rays += tile.rays;
      s.busySeconds += tile.seconds;
    } else {
      ++stats_[rank].duplicates;
    }
    changed_.notify_all();
  }

  void reclaimExpiredLeases() {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (int rank : scheduler_.reclaimExpired(now())) stats_[rank].retired = true;
    changed_.notify_all();
  }

  void retire(int rank) {
    const std::lock_guard<std::mutex> lock(mutex_);
    scheduler_.retire(rank);
    stats_[rank].retired = true;
    changed_.notify_all();
  }

  uint32_t frameId() const { return frameId_; }

  void recordProgress(int rank, const wire::ProgressMessage& progress) {
    const std::lock_guard<std::mutex> lock(mutex_);
    scheduler_.heardFrom(rank, now());
    if (progress.frame != frameId_) return;  // counts of an earlier frame
    stats_[rank].lostTiles += scheduler_.reconcile(rank, progress.jobsReceived, progress.heldTiles);
    changed_.notify_all();
  }

  void recordReady(int rank, double buildSeconds, int threads) {
    const std::lock_guard<std::mutex> lock(mutex_);
    stats_[rank].buildSeconds = buildSeconds;
    stats_[rank].threads = threads;
  }

  void abandon() {
    const std::lock_guard<std::mutex> lock(mutex_);
    abandoned_ = true;
    changed_.notify_all();
  }

  bool complete() {
    const std::lock_guard<std::mutex> lock(mutex_);
    return framebuffer_.complete();
  }
  size_t tilesDone() {
    const std::lock_guard<std::mutex> lock(mutex_);
    return framebuffer_.tilesDone();
  }
  size_t outstanding(int rank) {
    const std::lock_guard<std::mutex> lock(mutex_);
    return scheduler_.outstanding(rank);
  }
  bool retired(int rank) {
    const std::lock_guard<std::mutex> lock(mutex_);
    return scheduler_.retired(rank);
  }

  void waitForChange(std::chrono::milliseconds timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait_for(lock, timeout);
  }

  // Only after every thread has stopped.
  const ImageRgb& image() const { return framebuffer_.image(); }
  const std::vector<bool>& tileDone() const { return framebuffer_.received(); }
  std::vector<WorkerStats>& stats() { return stats_; }
  const std::vector<double>& tileSeconds() const { return tileSeconds_; }
  size_t reissued() const { return scheduler_.reissuedCount(); }

 private:
  // Which ranks the scheduler may give tiles to (FrameOptions::masterRenders, activeSlaves).
  static std::vector<bool> activeWorkers(int workers, const FrameOptions& options) {
    std::vector<bool> active(static_cast<size_t>(workers), true);
    active[kLocalWorker] = options.masterRenders;
    for (int r = 1; r < workers; ++r) {
      active[r] = options.activeSlaves < 0 || r <= options.activeSlaves;
    }
    return active;
  }

  static bool sameRect(const TileRect& a, const TileRect& b) {
    return a.x == b.x && a.y == b.y && a.width == b.width && a.height == b.height;
  }

  const std::vector<TileRect>& rects_;
  std::shared_ptr<const RenderPass> pass_;
  uint32_t frameId_;
  std::mutex mutex_;
  std::condition_variable changed_;
  TileScheduler scheduler_;
  Framebuffer framebuffer_;
  std::vector<WorkerStats> stats_;
  std::vector<double> tileSeconds_;
  bool abandoned_ = false;
  Clock::time_point start_;
};

// Keeps every live slave supplied with `prefetch` tiles and takes in what they send.
void serviceSlaves(MpiSession& cluster, FrameState& state, int prefetch) {
  for (int rank = 1; rank < cluster.size(); ++rank) {
    if (state.retired(rank)) continue;
    while (state.outstanding(rank) < static_cast<size_t>(prefetch)) {
      const std::optional<TileJob> job = state.nextJobFor(rank);
      if (!job) break;
      if (!cluster.send(rank, wire::encodeTileJob(tileJobMessage(*job)))) {
        state.retire(rank);  // MPI knows it is gone: its tiles go back at once
        break;
      }
    }
  }
  const std::optional<IncomingMessage> incoming = cluster.waitForMessage(0.005);
  if (incoming) {
    const wire::Message message =
        wire::decodeMessage(incoming->bytes.data(), incoming->bytes.size());
    switch (message.type) {
      case wire::MessageType::TileResult: {
        const wire::TileResultMessage tile = wire::decodeTileResult(message);
        if (tile.frame == state.frameId()) state.accept(tile.result, incoming->source);
        break;
      }
      case wire::MessageType::PhotonShare:
        break;  // late share of a photon pass that was completed without it
      case wire::MessageType::Progress:
        state.recordProgress(incoming->source, wire::decodeProgress(message));
        break;
      case wire::MessageType::Ready: {
        const wire::ReadyMessage ready = wire::decodeReady(message);
        state.recordReady(incoming->source, ready.buildSeconds, ready.threads);
        break;
      }
      case wire::MessageType::Error:
        throw std::runtime_error("rank " + std::to_string(incoming->source) + ": " +
                                 wire::decodeError(message).text);
      default:
        throw std::runtime_error("rank " + std::to_string(incoming->source) +
                                 " sent an unexpected " + wire::messageTypeName(message.type) +
                                 " message");
    }
  }
  state.reclaimExpiredLeases();
}

}  // namespace

FrameResult renderFrame(const Scene& scene, const FrameOptions& options, MpiSession* cluster) {
  const auto start = Clock::now();
  const RenderSettings& settings = scene.settings();
  const int ranks = cluster ? cluster->size() : 1;
  TileWorkerPool pool(scene, options.threads);

  FrameResult result;
  result.threads = pool.threadCount();
  result.tileSize = options.tileSize > 0 ? options.tileSize
                                         : automaticTileSize(settings.width, settings.height,
                                                             pool.threadCount() * ranks);
  const std::vector<TileRect> rects = planTiles(settings.width, settings.height, result.tileSize);
  result.tileCount = rects.size();

  FrameState state(rects, ranks, options, settings.width, settings.height);
  if (options.masterRenders) {
    state.stats()[kLocalWorker].threads = pool.threadCount();
    pool.start([&] { return state.nextLocalJob(); },
               [&](const TileJob&, TileResult&& tile) { state.accept(tile, kLocalWorker); });
  } else {
    result.threads = 0;
  }

  try {
    auto lastProgress = Clock::now();
    while (!state.complete()) {
      if (pool.failed()) break;  // join() below rethrows the thread's exception
      if (options.stopRequested && options.stopRequested()) {
        result.interrupted = true;
        pool.cancel();
        break;
      }
      if (cluster && ranks > 1) {
        serviceSlaves(*cluster, state, options.prefetch);
      } else {
        state.waitForChange(std::chrono::milliseconds(100));
      }
      if (options.progress && Clock::now() - lastProgress > std::chrono::milliseconds(100)) {
        options.progress(state.tilesDone(), rects.size());
        lastProgress = Clock::now();
      }
    }
  } catch (...) {
    state.abandon();
    pool.join();
    throw;
  }
  state.abandon();  // releases threads still waiting after a failure
  pool.join();
  if (options.progress && !result.interrupted) options.progress(rects.size(), rects.size());

  result.image = state.image();
  result.tileDone = state.tileDone();
  result.workers = state.stats();
  result.tiles = rects;
  result.tileSeconds = state.tileSeconds();
  result.reissuedTiles = state.reissued();
  for (const WorkerStats& w : result.workers) {
    result.rays += w.rays;
    result.busyThreadSeconds += w.busySeconds;
  }
  if (ClusterRoster* roster = options.roster) {
    for (const WorkerStats& w : result.workers) {
      if (w.rank == kLocalWorker || static_cast<size_t>(w.rank) >= roster->retired.size()) continue;
      roster->threads[w.rank] = w.threads;
      roster->buildSeconds[w.rank] = w.buildSeconds;
      roster->retired[w.rank] = roster->retired[w.rank] || w.retired;
    }
  }
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

size_t FrameResult::tilesDone() const {
  return static_cast<size_t>(std::count(tileDone.begin(), tileDone.end(), true));
}

bool handleSlaveStatus(const wire::Message& message, int source, ClusterRoster& roster) {
  if (message.type == wire::MessageType::Error) {
    throw std::runtime_error("rank " + std::to_string(source) + ": " +
                             wire::decodeError(message).text);
  }
  if (message.type != wire::MessageType::Ready) return false;
  const wire::ReadyMessage ready = wire::decodeReady(message);
  roster.recordReady(source, ready.threads, ready.buildSeconds);
  return true;
}

}  // namespace prism
