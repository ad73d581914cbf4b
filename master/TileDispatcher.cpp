#include "master/TileDispatcher.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "wire/TileJobWire.h"

namespace prism {
namespace {

constexpr int kLocalRank = 0;  // rank 0's own render threads

bool sameRect(const TileRect& a, const TileRect& b) {
  return a.x == b.x && a.y == b.y && a.width == b.width && a.height == b.height;
}

// Which ranks the frame's scheduler may give tiles to.
std::vector<bool> activeRanks(int ranks, const FramePlan& plan) {
  std::vector<bool> active(static_cast<size_t>(ranks), true);
  active[kLocalRank] = plan.masterRenders;
  for (int r = 1; r < ranks; ++r) active[r] = plan.activeSlaves < 0 || r <= plan.activeSlaves;
  return active;
}

}  // namespace

struct TileDispatcher::Frame {
  FramePlan plan;
  FrameListener* listener;
  TileScheduler scheduler;
  size_t done = 0;
  std::vector<bool> viewSent;  // per rank

  Frame(FramePlan p, FrameListener* l, int ranks, const DistributionOptions& o)
      : plan(std::move(p)),
        listener(l),
        scheduler(plan.tiles.size(), ranks, o.schedule, o.leaseSeconds, activeRanks(ranks, plan)),
        viewSent(static_cast<size_t>(ranks), false) {
    scheduler.exemptFromLeases(kLocalRank);
    viewSent[kLocalRank] = true;
  }
  bool complete() const { return done == plan.tiles.size(); }
};

TileDispatcher::TileDispatcher(const Scene& scene, SlaveLink& link,
                               const DistributionOptions& options)
    : scene_(scene),
      link_(link),
      options_(options),
      pool_(scene, options.threads),
      start_(SteadyClock::now()) {
  for (int r = 0; r < link_.ranks(); ++r) {
    RankStats s;  // what the roster knows; the counts are this dispatcher's own
    s.rank = r;
    s.threads = link_.rank(r).threads;
    s.buildSeconds = link_.rank(r).buildSeconds;
    s.retired = link_.rank(r).retired;
    delivered_.push_back(s);
  }
}

TileDispatcher::~TileDispatcher() {
  stop();
  try {
    pool_.join();
  } catch (...) {  // a destructor after a failure: the failure was reported by join() or lost
  }
}

int TileDispatcher::liveThreads() {
  const std::lock_guard<std::mutex> lock(mutex_);
  int threads = 0;
  for (const RankStats& r : delivered_) {
    if (!r.retired) threads += r.threads > 0 ? r.threads : pool_.threadCount();
  }
  return threads;
}

void TileDispatcher::startLocalWorkers() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    delivered_[kLocalRank].threads = pool_.threadCount();
  }
  pool_.start([this] { return nextLocalJob(); },
              [this](const TileJob& job, TileResult&& tile) {
                accept(job.frame, std::move(tile), kLocalRank);
              });
}

void TileDispatcher::beginFrame(FramePlan plan, FrameListener* listener) {
  std::vector<std::vector<std::vector<uint8_t>>> slaveJobs(static_cast<size_t>(link_.ranks()));
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (frame_) reissuedBefore_ += frame_->scheduler.reissuedCount();
    frame_ = std::make_unique<Frame>(std::move(plan), listener, link_.ranks(), options_);
    for (int r = 1; r < link_.ranks(); ++r) {
      // What photon passes and earlier frames learnt of the slaves.
      RankStats& s = delivered_[static_cast<size_t>(r)];
      s.retired = s.retired || link_.retired(r);
      if (link_.rank(r).threads > 0) s.threads = link_.rank(r).threads;
      if (s.retired) frame_->scheduler.retire(r);
    }
    // The slaves' first jobs are taken before rank 0's render threads can see the frame: their
    // round trip overlaps rank 0's first tiles, and even a frame rank 0 could finish alone
    // in a moment reaches every slave.
    for (int r = 1; r < link_.ranks(); ++r) slaveJobs[static_cast<size_t>(r)] = jobsForLocked(r);
  }
  for (int r = 1; r < link_.ranks(); ++r) sendJobs(r, slaveJobs[static_cast<size_t>(r)]);
  changed_.notify_all();
}

void TileDispatcher::endFrame(uint32_t frame) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (!frame_ || frame_->plan.frame != frame) return;
    reissuedBefore_ += frame_->scheduler.reissuedCount();
    frame_.reset();
  }
  changed_.notify_all();
}

bool TileDispatcher::frameComplete() {
  const std::lock_guard<std::mutex> lock(mutex_);
  return frame_ && frame_->complete();
}

size_t TileDispatcher::tilesDone() {
  const std::lock_guard<std::mutex> lock(mutex_);
  return frame_ ? frame_->done : 0;
}

std::optional<TileJob> TileDispatcher::nextLocalJob() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    if (stopped_) return std::nullopt;
    if (frame_) {
      if (const auto tile = frame_->scheduler.next(kLocalRank, now())) {
        const FramePlan& plan = frame_->plan;
        if (frame_->listener) frame_->listener->tileAssigned(plan.frame, *tile, kLocalRank);
        return TileJob(*tile, plan.tiles[*tile], plan.frame, plan.view, plan.light);
      }
    }
    // Tiles can appear later (a new frame, re-issued leases): every such change notifies.
    changed_.wait_for(lock, std::chrono::milliseconds(50));
  }
}

void TileDispatcher::accept(uint32_t frameId, TileResult&& tile, int rank) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    RankStats& s = delivered_[static_cast<size_t>(rank)];
    Frame* frame = frame_.get();
    const bool current = frame && frameId == frame->plan.frame;
    const bool planned = current && tile.tileIndex < frame->plan.tiles.size() &&
                         sameRect(tile.rect, frame->plan.tiles[tile.tileIndex]);
    if (!planned || !frame->scheduler.complete(tile.tileIndex, rank, now())) {
      ++s.staleTiles;
      return;
    }
    ++s.tiles;
    s.rays += tile.rays;
    s.busySeconds += tile.seconds;
    ++frame->done;
    if (frame->listener) frame->listener->tileFinished(frameId, std::move(tile), rank);
  }
  wake();  // the coordinator feeds, or finishes the frame, at once
}

void TileDispatcher::wake() {
  changed_.notify_all();
  link_.wake();
}

std::vector<std::vector<uint8_t>> TileDispatcher::jobsForLocked(int rank) {
  std::vector<std::vector<uint8_t>> outgoing;
  Frame* frame = frame_.get();
  if (!frame || frame->complete() || frame->scheduler.retired(rank)) return outgoing;
  const FramePlan& plan = frame->plan;
  // prefetch tiles per render thread: a slave of T threads renders T tiles at once, and
  // with a fixed count per slave most of a many-threaded rank's threads would idle.
  const size_t inFlight = static_cast<size_t>(options_.prefetch) *
                          static_cast<size_t>(std::max(1, link_.rank(rank).threads));
  while (frame->scheduler.outstanding(rank) < inFlight) {
    const auto tile = frame->scheduler.next(rank, now());
    if (!tile) break;
    if (plan.view && !frame->viewSent[rank]) {
      outgoing.push_back(wire::encodeView({plan.frame, *plan.view}));
      frame->viewSent[rank] = true;
    }
    outgoing.push_back(wire::encodeTileJob(
        tileJobMessage(TileJob(*tile, plan.tiles[*tile], plan.frame, nullptr, plan.light))));
    if (frame->listener) frame->listener->tileAssigned(plan.frame, *tile, rank);
  }
  return outgoing;
}

void TileDispatcher::sendJobs(int rank, std::vector<std::vector<uint8_t>>& jobs) {
  for (std::vector<uint8_t>& bytes : jobs) {
    if (!link_.send(rank, std::move(bytes))) {
      retireRank(rank);  // the transport knows it is gone: its tiles go back at once
      return;
    }
  }
}

void TileDispatcher::feedSlaves() {
  for (int rank = 1; rank < link_.ranks(); ++rank) {
    std::vector<std::vector<uint8_t>> jobs;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      jobs = jobsForLocked(rank);
    }
    sendJobs(rank, jobs);
  }
}

void TileDispatcher::retireRank(int rank) {
  link_.retire(rank);
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    delivered_[static_cast<size_t>(rank)].retired = true;
    if (frame_) frame_->scheduler.retire(rank);
  }
  changed_.notify_all();
}

void TileDispatcher::route(const SlaveMessage& incoming) {
  const int rank = incoming.source;
  const wire::Message& message = incoming.message;
  switch (message.type) {
    case wire::MessageType::TileResult: {
      wire::TileResultMessage result = wire::decodeTileResult(message);
      accept(result.frame, std::move(result.result), rank);
      return;
    }
    case wire::MessageType::Progress: {
      const wire::ProgressMessage progress = wire::decodeProgress(message);
      {
        const std::lock_guard<std::mutex> lock(mutex_);
        if (!frame_ || progress.frame != frame_->plan.frame) return;  // counts of another frame
        delivered_[static_cast<size_t>(rank)].lostTiles +=
            frame_->scheduler.reconcile(rank, progress.jobsReceived, progress.heldTiles);
      }
      changed_.notify_all();
      return;
    }
    case wire::MessageType::PhotonShare:  // of a photon pass completed without it
    case wire::MessageType::Echo:         // of a link probe that gave up on it
      return;
    default:
      throw std::runtime_error("rank " + std::to_string(rank) + " sent an unexpected " +
                               wire::messageTypeName(message.type) + " message");
  }
}

void TileDispatcher::service(double waitSeconds) {
  if (!link_.hasSlaves()) {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait_for(lock, std::chrono::duration<double>(waitSeconds),
                      [this] { return stopped_ || (frame_ && frame_->complete()); });
    return;
  }
  feedSlaves();
  // Everything that has arrived, then the silence check, so a slave is never judged silent
  // while its heartbeat waits in the queue.
  constexpr int kMaxMessagesPerStep = 256;
  double wait = waitSeconds;
  for (int n = 0; n < kMaxMessagesPerStep; ++n) {
    const std::optional<SlaveMessage> message = link_.receive(wait);
    wait = 0.0;
    if (!message) {
      if (n > 0 || waitSeconds == 0.0) break;
      continue;  // status only (a Ready): look once more without waiting
    }
    route(*message);
  }
  for (int rank : link_.retireSilent()) retireRank(rank);
  std::vector<int> expired;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (frame_) expired = frame_->scheduler.reclaimExpired(now());
    for (int r = 0; r < link_.ranks(); ++r) {  // what Ready messages said meanwhile
      RankStats& s = delivered_[static_cast<size_t>(r)];
      if (r > 0) s.threads = link_.rank(r).threads;
      s.buildSeconds = link_.rank(r).buildSeconds;
    }
  }
  for (int rank : expired) retireRank(rank);
}

void TileDispatcher::stop() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopped_ = true;
  }
  wake();
}

void TileDispatcher::cancel() {
  pool_.cancel();
  stop();
}

void TileDispatcher::join() {
  pool_.join();
}

std::vector<RankStats> TileDispatcher::stats() {
  const std::lock_guard<std::mutex> lock(mutex_);
  return delivered_;
}

size_t TileDispatcher::reissuedTiles() {
  const std::lock_guard<std::mutex> lock(mutex_);
  return reissuedBefore_ + (frame_ ? frame_->scheduler.reissuedCount() : 0);
}

}  // namespace prism
