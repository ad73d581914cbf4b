#include "master/dispatch/WorkDispatcher.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include "master/dispatch/ShareBatch.h"
#include "util/ThreadCount.h"
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

struct WorkDispatcher::Frame {
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
        scheduler(plan.tiles.size(), ranks, plan.schedule, o.leaseSeconds,
                  activeRanks(ranks, plan)),
        viewSent(static_cast<size_t>(ranks), false) {
    scheduler.exemptFromLeases(kLocalRank);
    viewSent[kLocalRank] = true;
  }
  ~Frame() { *ended = true; }
  Frame(const Frame&) = delete;
  Frame& operator=(const Frame&) = delete;
  bool complete() const { return done == plan.tiles.size(); }
};

WorkDispatcher::WorkDispatcher(const Scene& scene, Transport* cluster,
                               const DistributionOptions& options)
    : scene_(scene),
      options_(options),
      link_(cluster, options),
      pool_(scene, ThreadCount::resolve(options.threads)),
      start_(SteadyClock::now()) {}

WorkDispatcher::~WorkDispatcher() {
  stop();
  try {
    pool_.join();
  } catch (...) {  // a destructor after a failure: the failure was reported by join() or lost
  }
}

int WorkDispatcher::liveThreads() {
  int threads = 0;
  for (const RankStats& r : link_.roster()) {
    if (!r.retired) threads += r.threads > 0 ? r.threads : pool_.threadCount();
  }
  return threads;
}

void WorkDispatcher::startLocalWorkers() {
  if (pool_.started()) return;
  link_.setLocalThreads(pool_.threadCount());
  pool_.start([this] { return nextLocalJob(); },
              [this](const TileJob& job, TileResult&& tile) {
                accept(job.frame, std::move(tile), kLocalRank);
              });
}

WorkDispatcher::Frame* WorkDispatcher::findLocked(uint32_t frame) {
  for (const std::unique_ptr<Frame>& f : frames_) {
    if (f->plan.frame == frame) return f.get();
  }
  return nullptr;
}

void WorkDispatcher::beginFrame(FramePlan plan, FrameListener* listener) {
  addFrame(std::move(plan), listener, true);
}

void WorkDispatcher::queueFrame(FramePlan plan, FrameListener* listener) {
  addFrame(std::move(plan), listener, false);
}

void WorkDispatcher::runOpening(bool rank0Renders) {
  if (!geometryRecord_) return;
  GeometrySharePlan& record = *std::exchange(geometryRecord_, nullptr);
  broadcastGeometry(*link_.transport(), scene_.geometry(), rank0Renders, record);
}

void WorkDispatcher::addFrame(FramePlan plan, FrameListener* listener, bool endEarlier) {
  std::vector<std::vector<std::vector<uint8_t>>> slaveJobs(static_cast<size_t>(link_.ranks()));
  const bool opening = openingPending();
  const bool rank0Renders = plan.masterRenders && pool_.started();
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
      if (link_.retired(r)) frame.scheduler.retire(r);  // found gone by photon passes, or earlier
    }
    // The slaves' first jobs are taken before rank 0's render threads can see the frame: their
    // round trip overlaps rank 0's first tiles, and even a frame rank 0 could finish alone
    // in a moment reaches every slave. Not while the slaves still wait for the opening
    // broadcast: rank 0's threads start on the frame, and the slaves' leases begin after it.
    if (!opening) {
      for (int r = 1; r < link_.ranks(); ++r) {
        slaveJobs[static_cast<size_t>(r)] = jobsForLocked(r);
      }
    }
  }
  if (opening) {
    changed_.notify_all();
    runOpening(rank0Renders);
    const std::lock_guard<std::mutex> lock(mutex_);
    for (int r = 1; r < link_.ranks(); ++r) slaveJobs[static_cast<size_t>(r)] = jobsForLocked(r);
  }
  // A slave's tiles are told assigned before it can send them back.
  deliverNews();
  for (int r = 1; r < link_.ranks(); ++r) sendJobs(r, slaveJobs[static_cast<size_t>(r)]);
  changed_.notify_all();
}

void WorkDispatcher::endFrame(uint32_t frame) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (auto it = frames_.begin(); it != frames_.end(); ++it) {
      if ((*it)->plan.frame != frame) continue;
      reissuedBefore_ += (*it)->scheduler.reissuedCount();
      frames_.erase(it);
      break;
    }
  }
  // Its accepted tiles still queued are told now, and a call to its listener under way on
  // another thread ends before this returns (delivering_ is held meanwhile).
  deliverNews();
  changed_.notify_all();
}

bool WorkDispatcher::frameComplete() {
  const std::lock_guard<std::mutex> lock(mutex_);
  return !frames_.empty() && frames_.back()->complete();
}

size_t WorkDispatcher::tilesDone() {
  const std::lock_guard<std::mutex> lock(mutex_);
  return frames_.empty() ? 0 : frames_.back()->done;
}

std::optional<TileJob> WorkDispatcher::nextLocalJob() {
  std::optional<TileJob> job;
  bool told = false;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!job) {
      if (stopped_) return std::nullopt;
      for (const std::unique_ptr<Frame>& frame : frames_) {  // the oldest frame's tiles first
        if (const auto tile = frame->scheduler.next(kLocalRank, now())) {
          const FramePlan& plan = frame->plan;
          if (frame->listener) {
            news_.push_back({frame->listener, plan.frame, *tile, kLocalRank, {}});
            told = true;
          }
          job.emplace(*tile, plan.tiles[*tile], plan.frame, plan.view, plan.light);
          job->frameEnded = frame->ended;
          break;
        }
      }
      // Tiles can appear later (a new frame, re-issued leases): every such change notifies.
      if (!job) changed_.wait_for(lock, std::chrono::milliseconds(50));
    }
  }
  if (told) deliverNews();  // told assigned before this thread can finish it
  return job;
}

bool WorkDispatcher::listenerWants(uint32_t frameId) {
  const auto listenerOf = [this](uint32_t id) -> std::optional<FrameListener*> {
    const std::lock_guard<std::mutex> lock(mutex_);
    const Frame* frame = findLocked(id);
    if (!frame) return std::nullopt;
    return frame->listener;
  };
  const std::optional<FrameListener*> first = listenerOf(frameId);
  if (!first || !*first) return first.has_value();
  // delivering_ keeps the listener alive while it is asked: endFrame waits for it. Taken
  // before mutex_, so the frame is looked up again under both.
  const std::lock_guard<std::recursive_mutex> delivering(delivering_);
  const std::optional<FrameListener*> listener = listenerOf(frameId);
  if (!listener) return false;
  return !*listener || (*listener)->wantsTiles(frameId);
}

void WorkDispatcher::deliverNews() {
  const std::lock_guard<std::recursive_mutex> delivering(delivering_);
  for (;;) {
    std::optional<News> next;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (news_.empty()) return;
      next.emplace(std::move(news_.front()));
      news_.pop_front();
    }
    News& n = *next;
    if (n.finished) {
      n.listener->tileFinished(n.frame, std::move(*n.finished), n.rank);
    } else {
      n.listener->tileAssigned(n.frame, n.tile, n.rank);
    }
  }
}

void WorkDispatcher::accept(uint32_t frameId, TileResult&& tile, int rank) {
  const bool wanted = listenerWants(frameId);
  bool frameDone = false;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    Frame* frame = findLocked(frameId);
    const bool planned = wanted && frame && tile.tileIndex < frame->plan.tiles.size() &&
                         sameRect(tile.rect, frame->plan.tiles[tile.tileIndex]);
    if (!planned || !frame->scheduler.complete(tile.tileIndex, rank, now())) {
      link_.countStale(rank);
      return;
    }
    link_.countDelivered(rank, tile);
    ++frame->done;
    if (frame->listener) {
      const uint32_t index = tile.tileIndex;
      news_.push_back({frame->listener, frameId, index, rank, std::move(tile)});
    }
    frameDone = frame->complete();
    // A complete frame behind the current one has nothing left to do here.
    if (frameDone && frame != frames_.back().get()) {
      reissuedBefore_ += frame->scheduler.reissuedCount();
      frames_.erase(std::find_if(frames_.begin(), frames_.end(),
                                 [frame](const auto& f) { return f.get() == frame; }));
    }
  }
  deliverNews();
  // The coordinator finishes the frame at once. A tile alone changes nothing it waits for (a
  // slave's load is its own tiles), so it is not woken for one: with every core rendering, each
  // wake-up would preempt a render thread. A listener wakes it for news it wants sooner.
  if (frameDone) wake();
}

void WorkDispatcher::wake() {
  changed_.notify_all();
  link_.wake();
}

std::vector<std::vector<uint8_t>> WorkDispatcher::jobsForLocked(int rank) {
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
      if (frame->listener) news_.push_back({frame->listener, plan.frame, *tile, rank, {}});
    }
  }
  return outgoing;
}

void WorkDispatcher::sendJobs(int rank, std::vector<std::vector<uint8_t>>& jobs) {
  for (std::vector<uint8_t>& bytes : jobs) {
    if (!link_.send(rank, std::move(bytes))) {
      retireRank(rank);  // the transport knows it is gone: its tiles go back at once
      return;
    }
  }
}

void WorkDispatcher::feedSlaves() {
  for (int rank = 1; rank < link_.ranks(); ++rank) {
    std::vector<std::vector<uint8_t>> jobs;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      jobs = jobsForLocked(rank);
    }
    deliverNews();  // told assigned before the slave can send them back
    sendJobs(rank, jobs);
  }
}

void WorkDispatcher::retireRank(int rank) {
  link_.retire(rank);
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (const std::unique_ptr<Frame>& frame : frames_) frame->scheduler.retire(rank);
    if (shares_) shares_->scheduler.retire(rank);  // its share goes back, for rank 0
  }
  changed_.notify_all();
}

void WorkDispatcher::route(const SlaveMessage& incoming) {
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
        link_.countLost(
            rank, frame->scheduler.reconcile(rank, progress.jobsReceived, progress.heldTiles));
      }
      changed_.notify_all();
      return;
    }
    case wire::MessageType::PhotonShare:
    case wire::MessageType::PhotonRadiiShare:
      routeShare(incoming);  // a share's answer, or a late one of a pass done without it
      return;
    case wire::MessageType::Echo:  // of a link probe that gave up on it
      return;
    default:
      throw std::runtime_error("rank " + std::to_string(rank) + " sent an unexpected " +
                               wire::messageTypeName(message.type) + " message");
  }
}

void WorkDispatcher::service(double waitSeconds) {
  runOpening(false);
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
    std::vector<TileScheduler*> schedulers;
    for (const std::unique_ptr<Frame>& frame : frames_) schedulers.push_back(&frame->scheduler);
    if (shares_) schedulers.push_back(&shares_->scheduler);  // a slave still building its scene
    for (TileScheduler* scheduler : schedulers) {
      for (int rank : scheduler->reclaimExpired(now())) {
        if (std::find(expired.begin(), expired.end(), rank) == expired.end()) {
          expired.push_back(rank);
        }
      }
    }
  }
  for (int rank : expired) retireRank(rank);
}

void WorkDispatcher::stop() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopped_ = true;
  }
  wake();
}

void WorkDispatcher::cancel() {
  pool_.cancel();
  stop();
}

void WorkDispatcher::join() {
  pool_.join();
}

size_t WorkDispatcher::reissuedTiles() {
  const std::lock_guard<std::mutex> lock(mutex_);
  size_t reissued = reissuedBefore_;
  for (const std::unique_ptr<Frame>& frame : frames_) reissued += frame->scheduler.reissuedCount();
  return reissued;
}

}  // namespace prism
