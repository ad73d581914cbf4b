#include "master/LiveRenderer.h"

#include <algorithm>
#include <stdexcept>

#include "master/TilePlan.h"
#include "math/Random.h"
#include "transport/MpiSession.h"
#include "wire/Messages.h"

namespace prism {
namespace {

constexpr int kLocalWorker = 0;  // rank 0's own render threads

bool sameRect(const TileRect& a, const TileRect& b) {
  return a.x == b.x && a.y == b.y && a.width == b.width && a.height == b.height;
}

}  // namespace

struct LiveRenderer::Event {
  enum class Kind { Assigned, Finished, PassFinished } kind;
  uint32_t frame = 0;
  uint32_t tile = 0;
  int rank = 0;
  std::shared_ptr<const TileResult> result;
  double seconds = 0.0;
};

struct LiveRenderer::Pass {
  PassInfo info;
  TileScheduler scheduler;
  size_t done = 0;
  bool finished = false;
  double started = 0.0;
  double busySeconds = 0.0;
  std::vector<bool> viewSent;  // per rank: the View message went out

  Pass(PassInfo i, int ranks, const LiveOptions& o, double now)
      : info(std::move(i)),
        scheduler(info.tiles.size(), ranks, o.schedule, o.leaseSeconds),
        started(now),
        viewSent(static_cast<size_t>(ranks), false) {
    scheduler.exemptFromLeases(kLocalWorker);
  }
};

uint64_t LiveRenderer::passSeed(uint64_t sceneSeed, int pass) {
  if (pass <= 1) return sceneSeed;
  return mix64(sceneSeed ^ mix64(static_cast<uint64_t>(pass) * 0x9e3779b97f4a7c15ULL));
}

LiveRenderer::LiveRenderer(const Scene& scene, const LiveOptions& options, MpiSession* cluster)
    : scene_(scene),
      options_(options),
      cluster_(cluster),
      ranks_(cluster ? cluster->size() : 1),
      pool_(scene, options.threads),
      start_(SteadyClock::now()),
      lastStats_(start_) {
  stats_.resize(static_cast<size_t>(ranks_));
  for (int r = 0; r < ranks_; ++r) stats_[r].rank = r;
  stats_[kLocalWorker].threads = pool_.threadCount();
}

LiveRenderer::~LiveRenderer() {
  stop();
}

void LiveRenderer::setView(const ViewSettings& view) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    pendingView_ = view;
    pendingSince_ = SteadyClock::now();
  }
  changed_.notify_all();
}

void LiveRenderer::stop() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopped_ = true;
  }
  changed_.notify_all();
}

void LiveRenderer::beginPassLocked(int index, std::vector<PassInfo>& started) {
  const RenderSettings& settings = scene_.settings();
  PassInfo info;
  info.frame = nextFrame_++;
  info.viewId = viewId_;
  info.pass = index;
  info.scale = index == 0 ? std::max(options_.previewScale, 1) : 1;
  auto view = std::make_shared<RenderView>();
  view->camera = view_.camera;
  view->width = std::max(1, settings.width / info.scale);
  view->height = std::max(1, settings.height / info.scale);
  view->samplesPerPixel = index == 0 ? 1 : view_.samplesPerPixel;
  view->seed = passSeed(settings.seed, index);
  view->debugView = view_.debugView;
  info.view = view;
  int threads = 0;
  for (const RankStats& r : stats_) {
    if (!r.retired) threads += r.threads > 0 ? r.threads : pool_.threadCount();
  }
  const int tileSize = options_.tileSize > 0
                           ? std::max(8, options_.tileSize / info.scale)
                           : automaticTileSize(view->width, view->height, threads);
  info.tiles = planTiles(view->width, view->height, tileSize);
  pass_ = std::make_unique<Pass>(info, ranks_, options_, now());
  for (int r = 0; r < ranks_; ++r) {
    if (stats_[r].retired) pass_->scheduler.retire(r);
  }
  pass_->viewSent[kLocalWorker] = true;
  started.push_back(std::move(info));
}

void LiveRenderer::startNextPassLocked(std::vector<PassInfo>& started) {
  if (pendingView_) {
    view_ = *pendingView_;
    pendingView_.reset();
    ++viewId_;
    viewSince_ = pendingSince_;
    live_.passesDone = 0;
    live_.previewLatencySeconds = 0.0;
    live_.firstFullSeconds = 0.0;
    beginPassLocked(options_.previewScale > 1 ? 0 : 1, started);
  } else if (pass_ && pass_->finished && pass_->info.pass < options_.maxPasses) {
    beginPassLocked(pass_->info.pass + 1, started);
  }
}

std::optional<TileJob> LiveRenderer::nextLocalJob() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    if (stopped_) return std::nullopt;
    if (pass_ && !pass_->finished && !pendingView_) {
      if (const auto tile = pass_->scheduler.next(kLocalWorker, now())) {
        events_.push_back(
            {Event::Kind::Assigned, pass_->info.frame, *tile, kLocalWorker, nullptr, 0.0});
        changed_.notify_all();
        return TileJob{*tile, pass_->info.tiles[*tile], pass_->info.frame, pass_->info.view};
      }
    }
    changed_.wait_for(lock, std::chrono::milliseconds(20));
  }
}

void LiveRenderer::accept(uint32_t frame, TileResult&& tile, int rank) {
  const std::lock_guard<std::mutex> lock(mutex_);
  RankStats& s = stats_[rank];
  if (!pass_ || frame != pass_->info.frame) {
    ++s.staleTiles;  // a frame the viewer has moved on from
    return;
  }
  Pass& p = *pass_;
  const bool planned =
      tile.tileIndex < p.info.tiles.size() && sameRect(tile.rect, p.info.tiles[tile.tileIndex]);
  if (!planned || !p.scheduler.complete(tile.tileIndex, rank, now())) {
    ++s.staleTiles;
    return;
  }
  ++s.tiles;
  s.busySeconds += tile.seconds;
  s.rays += tile.rays;
  p.busySeconds += tile.seconds;
  const uint32_t index = tile.tileIndex;
  events_.push_back({Event::Kind::Finished, frame, index, rank,
                     std::make_shared<const TileResult>(std::move(tile)), 0.0});
  if (++p.done == p.info.tiles.size()) {
    p.finished = true;
    const double seconds = now() - p.started;
    const double sinceView = secondsSince(viewSince_);
    if (p.info.pass == 0) {
      live_.previewLatencySeconds = sinceView;
    } else {
      ++live_.passesDone;
      live_.lastPassSeconds = seconds;
      live_.lastPassBusySeconds = p.busySeconds;
      if (p.info.pass == 1) live_.firstFullSeconds = sinceView;
    }
    events_.push_back({Event::Kind::PassFinished, frame, 0, rank, nullptr, seconds});
  }
  changed_.notify_all();
}

void LiveRenderer::serviceSlaves() {
  MpiSession& cluster = *cluster_;
  for (int rank = 1; rank < ranks_; ++rank) {
    std::vector<std::vector<uint8_t>> outgoing;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (!pass_ || pass_->finished || pass_->scheduler.retired(rank) || pendingView_) continue;
      if (!pass_->viewSent[rank]) {
        outgoing.push_back(wire::encodeView({pass_->info.frame, *pass_->info.view}));
        pass_->viewSent[rank] = true;
      }
      while (pass_->scheduler.outstanding(rank) < static_cast<size_t>(options_.prefetch)) {
        const auto tile = pass_->scheduler.next(rank, now());
        if (!tile) break;
        outgoing.push_back(
            wire::encodeTileJob({pass_->info.frame, *tile, pass_->info.tiles[*tile]}));
        events_.push_back({Event::Kind::Assigned, pass_->info.frame, *tile, rank, nullptr, 0.0});
      }
    }
    for (std::vector<uint8_t>& bytes : outgoing) {
      if (!cluster.send(rank, std::move(bytes))) {
        const std::lock_guard<std::mutex> lock(mutex_);
        stats_[rank].retired = true;  // MPI knows it is gone: its tiles go back at once
        if (pass_) pass_->scheduler.retire(rank);
        break;
      }
    }
  }
  const std::optional<IncomingMessage> incoming = cluster.waitForMessage(0.001);
  if (incoming) {
    const wire::Message message =
        wire::decodeMessage(incoming->bytes.data(), incoming->bytes.size());
    const int rank = incoming->source;
    switch (message.type) {
      case wire::MessageType::TileResult: {
        wire::TileResultMessage result = wire::decodeTileResult(message);
        accept(result.frame, std::move(result.result), rank);
        break;
      }
      case wire::MessageType::Progress: {
        // Only a heartbeat here: its job count spans frames, so it cannot name lost tiles.
        const std::lock_guard<std::mutex> lock(mutex_);
        if (pass_) pass_->scheduler.heardFrom(rank, now());
        break;
      }
      case wire::MessageType::Ready: {
        const wire::ReadyMessage ready = wire::decodeReady(message);
        const std::lock_guard<std::mutex> lock(mutex_);
        stats_[rank].threads = ready.threads;
        break;
      }
      case wire::MessageType::Error:
        throw std::runtime_error("rank " + std::to_string(rank) + ": " +
                                 wire::decodeError(message).text);
      default:
        throw std::runtime_error("rank " + std::to_string(rank) + " sent an unexpected " +
                                 wire::messageTypeName(message.type) + " message");
    }
  }
  const std::lock_guard<std::mutex> lock(mutex_);
  if (pass_) {
    for (int rank : pass_->scheduler.reclaimExpired(now())) stats_[rank].retired = true;
  }
}

LiveStats LiveRenderer::statsLocked(double elapsedSeconds) {
  LiveStats s = live_;
  s.ranks = stats_;
  if (pass_) {
    s.frame = pass_->info.frame;
    s.viewId = pass_->info.viewId;
    s.pass = pass_->info.pass;
  }
  RayCounters total;
  s.totalThreads = 0;
  for (const RankStats& r : stats_) {
    total += r.rays;
    if (!r.retired) s.totalThreads += r.threads;
  }
  s.raysPerSecond = static_cast<double>(total.total() - raysAtLastStats_.total()) /
                    std::max(elapsedSeconds, 1e-3);
  raysAtLastStats_ = total;
  return s;
}

LiveStats LiveRenderer::stats() {
  const std::lock_guard<std::mutex> lock(mutex_);
  const double elapsed = secondsSince(lastStats_);
  lastStats_ = SteadyClock::now();
  return statsLocked(elapsed);
}

void LiveRenderer::run(LiveListener& listener) {
  pool_.start([this] { return nextLocalJob(); },
              [this](const TileJob& job, TileResult&& tile) {
                accept(job.frame, std::move(tile), kLocalWorker);
              });
  lastStats_ = SteadyClock::now();
  try {
    for (;;) {
      std::vector<PassInfo> started;
      std::deque<Event> events;
      {
        const std::lock_guard<std::mutex> lock(mutex_);
        if (stopped_ || pool_.failed()) break;
        startNextPassLocked(started);
        events.swap(events_);
      }
      if (!started.empty()) changed_.notify_all();  // wakes render threads waiting for work
      // Events first: they belong to the pass before the one just started.
      for (Event& e : events) {
        switch (e.kind) {
          case Event::Kind::Assigned:
            listener.tileAssigned(e.frame, e.tile, e.rank);
            break;
          case Event::Kind::Finished:
            listener.tileFinished(e.frame, std::move(e.result), e.rank);
            break;
          case Event::Kind::PassFinished:
            listener.passFinished(e.frame, e.seconds);
            break;
        }
      }
      for (const PassInfo& info : started) listener.passStarted(info);
      if (cluster_ && ranks_ > 1) {
        serviceSlaves();
      } else {
        std::unique_lock<std::mutex> lock(mutex_);
        changed_.wait_for(lock, std::chrono::milliseconds(2), [this] {
          return stopped_ || !events_.empty() || pendingView_ ||
                 (pass_ && pass_->finished && pass_->info.pass < options_.maxPasses);
        });
      }
      bool due = false;
      {
        const std::lock_guard<std::mutex> lock(mutex_);
        due = secondsSince(lastStats_) >= options_.statsInterval;
      }
      if (due) listener.statsUpdated(stats());
    }
  } catch (...) {
    stop();
    pool_.join();
    throw;
  }
  stop();
  pool_.join();  // rethrows a render thread's failure
}

}  // namespace prism
