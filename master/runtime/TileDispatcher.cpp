#include "master/runtime/TileDispatcher.h"

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
  // Set when the frame leaves (ended, or complete behind the current one): rank 0's threads
  // stop its tiles after their row (TileJob::frameEnded).
  std::shared_ptr<std::atomic<bool>> ended = std::make_shared<std::atomic<bool>>(false);

  Frame(FramePlan p, FrameListener* l, int ranks, const DistributionOptions& o)
      : plan(std::move(p)),
        listener(l),
        scheduler(plan.tiles.size(), ranks, o.schedule, o.leaseSeconds, activeRanks(ranks, plan)),
        viewSent(static_cast<size_t>(ranks), false) {
    scheduler.exemptFromLeases(kLocalRank);
    viewSent[kLocalRank] = true;
  }
  ~Frame() { *ended = true; }
  Frame(const Frame&) = delete;
  Frame& operator=(const Frame&) = delete;
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

TileDispatcher::Frame* TileDispatcher::findLocked(uint32_t frame) {
  for (const std::unique_ptr<Frame>& f : frames_) {
    if (f->plan.frame == frame) return f.get();
  }
  return nullptr;
}

void TileDispatcher::beginFrame(FramePlan plan, FrameListener* listener) {
  addFrame(std::move(plan), listener, true);
}

void TileDispatcher::queueFrame(FramePlan plan, FrameListener* listener) {
  addFrame(std::move(plan), listener, false);
}

void TileDispatcher::addFrame(FramePlan plan, FrameListener* listener, bool endEarlier) {
  std::vector<std::vector<std::vector<uint8_t>>> slaveJobs(static_cast<size_t>(link_.ranks()));
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    // Frames that are over leave: all of them when this one replaces them, else the complete.
    for (auto it = frames_.begin(); it != frames_.end();) {
      if (endEarlier || (*it)->complete()) {
        reissuedBefore_ += (*it)->scheduler.reissuedCount();
        it = frames_.erase(it);
      } else {
        ++it;
      }
    }
    frames_.push_back(std::make_unique<Frame>(std::move(plan), listener, link_.ranks(), options_));
    Frame& frame = *frames_.back();
    for (int r = 1; r < link_.ranks(); ++r) {
      // What photon passes and earlier frames learnt of the slaves.
      RankStats& s = delivered_[static_cast<size_t>(r)];
      s.retired = s.retired || link_.retired(r);
      if (link_.rank(r).threads > 0) s.threads = link_.rank(r).threads;
      if (s.retired) frame.scheduler.retire(r);
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
    for (auto it = frames_.begin(); it != frames_.end(); ++it) {
      if ((*it)->plan.frame != frame) continue;
      reissuedBefore_ += (*it)->scheduler.reissuedCount();
      frames_.erase(it);
      break;
    }
  }
  changed_.notify_all();
}

bool TileDispatcher::frameComplete() {
  const std::lock_guard<std::mutex> lock(mutex_);
  return !frames_.empty() && frames_.back()->complete();
}

size_t TileDispatcher::tilesDone() {
  const std::lock_guard<std::mutex> lock(mutex_);
  return frames_.empty() ? 0 : frames_.back()->done;
}

std::optional<TileJob> TileDispatcher::nextLocalJob() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    if (stopped_) return std::nullopt;
    for (const std::unique_ptr<Frame>& frame : frames_) {  // the oldest frame's tiles first
      if (const auto tile = frame->scheduler.next(kLocalRank, now())) {
        const FramePlan& plan = frame->plan;
        if (frame->listener) frame->listener->tileAssigned(plan.frame, *tile, kLocalRank);
        TileJob job(*tile, plan.tiles[*tile], plan.frame, plan.view, plan.light);
        job.frameEnded = frame->ended;
        return job;
      }
    }
    // Tiles can appear later (a new frame, re-issued leases): every such change notifies.
    changed_.wait_for(lock, std::chrono::milliseconds(50));
  }
}

void TileDispatcher::accept(uint32_t frameId, TileResult&& tile, int rank) {
  bool frameDone = false;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    RankStats& s = delivered_[static_cast<size_t>(rank)];
    Frame* frame = findLocked(frameId);
    const bool planned = frame && tile.tileIndex < frame->plan.tiles.size() &&
                         sameRect(tile.rect, frame->plan.tiles[tile.tileIndex]) &&
                         (!frame->listener || frame->listener->wantsTiles(frameId));
    if (!planned || !frame->scheduler.complete(tile.tileIndex, rank, now())) {
      ++s.staleTiles;
      return;
    }
    ++s.tiles;
    s.rays += tile.rays;
    s.busySeconds += tile.seconds;
    ++frame->done;
    if (frame->listener) frame->listener->tileFinished(frameId, std::move(tile), rank);
    frameDone = frame->complete();
    // A complete frame behind the current one has nothing left to do here.
    if (frameDone && frame != frames_.back().get()) {
      reissuedBefore_ += frame->scheduler.reissuedCount();
      frames_.erase(std::find_if(frames_.begin(), frames_.end(),
                                 [frame](const auto& f) { return f.get() == frame; }));
    }
  }
  // The coordinator finishes the frame at once. A tile alone changes nothing it waits for (a
  // slave's load is its own tiles), so it is not woken for one: with every core rendering, each
  // wake-up would preempt a render thread. A listener wakes it for news it wants sooner.
  if (frameDone) wake();
}

void TileDispatcher::wake() {
  changed_.notify_all();
  link_.wake();
}

std::vector<std::vector<uint8_t>> TileDispatcher::jobsForLocked(int rank) {
  std::vector<std::vector<uint8_t>> outgoing;
  // prefetch tiles per render thread: a slave of T threads renders T tiles at once, and
  // with a fixed count per slave most of a many-threaded rank's threads would idle.
  const size_t inFlight = static_cast<size_t>(options_.prefetch) *
                          static_cast<size_t>(std::max(1, link_.rank(rank).threads));
  size_t outstanding = 0;
  for (const std::unique_ptr<Frame>& frame : frames_) {
    outstanding += frame->scheduler.outstanding(rank);
  }
  // Frames older than the oldest running one are over; a View tells the slave so.
  const uint32_t liveFrom = frames_.empty() ? 0 : frames_.front()->plan.frame;
  for (const std::unique_ptr<Frame>& frame : frames_) {  // the oldest frame's tiles first
    if (frame->complete() || frame->scheduler.retired(rank)) continue;
    const FramePlan& plan = frame->plan;
    while (outstanding < inFlight) {
      const auto tile = frame->scheduler.next(rank, now());
      if (!tile) break;
      ++outstanding;
      if (plan.view && !frame->viewSent[rank]) {
        outgoing.push_back(wire::encode(wire::ViewMessage{plan.frame, liveFrom, *plan.view}));
        frame->viewSent[rank] = true;
      }
      outgoing.push_back(wire::encode(
          tileJobMessage(TileJob(*tile, plan.tiles[*tile], plan.frame, nullptr, plan.light))));
      if (frame->listener) frame->listener->tileAssigned(plan.frame, *tile, rank);
    }
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
    for (const std::unique_ptr<Frame>& frame : frames_) frame->scheduler.retire(rank);
  }
  changed_.notify_all();
}

void TileDispatcher::route(const SlaveMessage& incoming) {
  const int rank = incoming.source;
  const wire::Message& message = incoming.message;
  switch (message.type) {
    case wire::MessageType::TileResult: {
      wire::TileResultMessage result = wire::decode<wire::TileResultMessage>(message);
      accept(result.frame, std::move(result.result), rank);
      return;
    }
    case wire::MessageType::Progress: {
      const wire::ProgressMessage progress = wire::decode<wire::ProgressMessage>(message);
      {
        const std::lock_guard<std::mutex> lock(mutex_);
        Frame* frame = findLocked(progress.frame);
        if (!frame) return;  // counts of a frame that is over
        delivered_[static_cast<size_t>(rank)].lostTiles +=
            frame->scheduler.reconcile(rank, progress.jobsReceived, progress.heldTiles);
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
    changed_.wait_for(lock, std::chrono::duration<double>(waitSeconds), [this] {
      return stopped_ || (!frames_.empty() && frames_.back()->complete());
    });
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
    for (const std::unique_ptr<Frame>& frame : frames_) {
      for (int rank : frame->scheduler.reclaimExpired(now())) {
        if (std::find(expired.begin(), expired.end(), rank) == expired.end()) {
          expired.push_back(rank);
        }
      }
    }
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
  size_t reissued = reissuedBefore_;
  for (const std::unique_ptr<Frame>& frame : frames_) reissued += frame->scheduler.reissuedCount();
  return reissued;
}

}  // namespace prism
