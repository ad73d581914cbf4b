#include "master/LiveRenderer.h"

#include <algorithm>
#include <stdexcept>

#include "caustics/PhotonGather.h"
#include "master/CausticPasses.h"
#include "master/PhotonPass.h"
#include "master/TileJobWire.h"
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

// The next pass to render, chosen under the lock; its frame id is taken already.
struct LiveRenderer::PassPlan {
  int index = 0;
  uint32_t frame = 0;
  uint64_t viewId = 0;
  ViewSettings view;
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
      lastStats_(start_),
      roster_(ranks_),
      maxRadius_(scene.causticSettings().maxRadius > 0.0f ? scene.causticSettings().maxRadius
                                                          : automaticMaxRadius(scene)) {
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

void LiveRenderer::beginPassLocked(const PassPlan& plan, std::shared_ptr<const RenderPass> light,
                                   std::vector<PassInfo>& started) {
  const RenderSettings& settings = scene_.settings();
  const int index = plan.index;
  PassInfo info;
  info.frame = plan.frame;
  info.viewId = plan.viewId;
  info.pass = index;
  info.scale = index == 0 ? std::max(options_.previewScale, 1) : 1;
  auto view = std::make_shared<RenderView>();
  view->camera = plan.view.camera;
  view->width = std::max(1, settings.width / info.scale);
  view->height = std::max(1, settings.height / info.scale);
  view->samplesPerPixel = index == 0 ? 1 : plan.view.samplesPerPixel;
  view->seed = passSeed(settings.seed, index);
  view->debugView = plan.view.debugView;
  view->causticMapBlur = plan.view.causticMapBlur;
  info.view = view;
  info.light = std::move(light);
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

std::optional<LiveRenderer::PassPlan> LiveRenderer::nextPassLocked() {
  int index = 0;
  if (pendingView_) {
    view_ = *pendingView_;
    pendingView_.reset();
    ++viewId_;
    viewSince_ = pendingSince_;
    live_.passesDone = 0;
    live_.previewLatencySeconds = 0.0;
    live_.firstFullSeconds = 0.0;
    live_.photons = {};
    live_.photons.method = view_.caustics;
    pass_.reset();  // the old view's tiles are stale from now on, even while photons trace
    index = options_.previewScale > 1 ? 0 : 1;
  } else if (pass_ && pass_->finished && pass_->info.pass < options_.maxPasses) {
    index = pass_->info.pass + 1;
  } else {
    return std::nullopt;
  }
  return PassPlan{index, nextFrame_++, viewId_, view_};
}

std::shared_ptr<const CausticMapEstimator> LiveRenderer::causticMaps(bool blur) {
  const std::lock_guard<std::mutex> lock(mapsMutex_);
  std::shared_ptr<const CausticMapEstimator>& maps = causticMaps_[blur];
  if (!maps) {
    const auto start = SteadyClock::now();
    maps = std::make_shared<const CausticMapEstimator>(
        scene_, causticMapSettings(scene_.causticSettings(), blur), pool_.threadCount());
    mapBuildSeconds_[blur] = secondsSince(start);
  }
  return maps;
}

std::shared_ptr<const RenderPass> LiveRenderer::causticMapLight(const PassPlan& plan) {
  // Every rank builds the maps from the scene once per blur setting (a slave as soon as it has
  // a caustic-map scene, else when the first tile asks); they do not depend on the camera, so
  // the preview shows them too.
  const bool blur = plan.view.causticMapBlur;
  const std::shared_ptr<const CausticMapEstimator> maps = causticMaps(blur);
  double buildSeconds = 0.0;
  {
    const std::lock_guard<std::mutex> lock(mapsMutex_);
    buildSeconds = mapBuildSeconds_[blur];
  }
  const std::lock_guard<std::mutex> lock(mutex_);
  if (plan.viewId == viewId_) {
    PhotonLiveStats& s = live_.photons;
    s.noCasters = maps->empty();
    s.mapResolution = scene_.causticSettings().mapResolution;
    s.mapViews = maps->stats().views;
    s.mapBlur = blur;
    s.mapBuildSeconds = buildSeconds;
  }
  if (maps->empty()) return nullptr;
  return causticMapPass(plan.frame, maps);
}

std::shared_ptr<const RenderPass> LiveRenderer::passLight(const PassPlan& plan) {
  if (plan.view.debugView != DebugView::Image) return nullptr;  // debug views: no caustics
  if (plan.view.caustics == CausticMethod::CausticMap) return causticMapLight(plan);
  // The preview shows no photon-mapped caustics: a photon pass would delay it.
  if (plan.index == 0 || plan.view.caustics != CausticMethod::PhotonMap) return nullptr;
  const CausticSettings& c = scene_.causticSettings();
  const uint64_t budget = plan.view.photonsPerPass > 0 ? plan.view.photonsPerPass : c.photons;
  if (!tracer_ || tracerBudget_ != budget) {
    tracer_ = std::make_unique<PhotonTracer>(scene_, budget, c.maxBounces);
    tracerBudget_ = budget;
  }
  if (!tracer_->hasWork()) {
    const std::lock_guard<std::mutex> lock(mutex_);
    live_.photons.noCasters = true;
    return nullptr;  // like `prism render`: nothing to trace, a plain pass
  }
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (int r = 1; r < ranks_; ++r) {
      roster_.retired[r] = roster_.retired[r] || stats_[r].retired;
      if (stats_[r].threads > 0) roster_.threads[r] = stats_[r].threads;
    }
  }
  PhotonPassStats p;
  auto map = tracePhotonPass(*tracer_, plan.frame, pool_.threadCount(), cluster_, roster_,
                             options_.leaseSeconds, p);
  const float radius =
      plan.index == 1
          ? (c.radius > 0.0f ? c.radius : automaticProgressiveRadius(*map, c.gather, maxRadius_))
          : nextProgressiveRadius(radius_, plan.index, c.alpha);
  radius_ = radius;
  const PhotonGatherSettings gather{true, c.gather, radius, c.filter};
  sendPhotonMap(*map, plan.frame, gather, cluster_, roster_, p);

  const std::lock_guard<std::mutex> lock(mutex_);
  for (int r = 1; r < ranks_; ++r) {
    stats_[r].retired = stats_[r].retired || roster_.retired[r];
    if (roster_.threads[r] > 0) stats_[r].threads = roster_.threads[r];
  }
  if (plan.viewId == viewId_) {
    PhotonLiveStats& s = live_.photons;
    s.photonsPerPass = tracer_->photonsPerPass();
    ++s.passes;
    s.stored = map->size();
    s.mapBytes = p.mapBytes;
    s.traceSeconds = p.traceSeconds;
    s.buildSeconds = p.buildSeconds;
    s.distributeSeconds = p.distributeSeconds;
    s.photonsPerSecond = static_cast<double>(p.trace.emitted) / std::max(p.traceSeconds, 1e-6);
    s.radius = radius;
  }
  return std::make_shared<const RenderPass>(
      RenderPass{plan.frame, true, std::make_shared<const PhotonGather>(std::move(map), gather)});
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
        return TileJob{*tile, pass_->info.tiles[*tile], pass_->info.frame, pass_->info.view,
                       pass_->info.light};
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
        outgoing.push_back(wire::encodeTileJob(tileJobMessage(TileJob{
            *tile, pass_->info.tiles[*tile], pass_->info.frame, nullptr, pass_->info.light})));
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
      std::optional<PassPlan> plan;
      {
        const std::lock_guard<std::mutex> lock(mutex_);
        if (stopped_ || pool_.failed()) break;
        plan = nextPassLocked();
        events.swap(events_);
      }
      if (plan) {
        // Photons are traced here, without the lock: the GUI thread can still ask for views.
        std::shared_ptr<const RenderPass> light = passLight(*plan);
        const std::lock_guard<std::mutex> lock(mutex_);
        // A view asked for meanwhile wins; this pass is dropped before it starts.
        if (!pendingView_ && plan->viewId == viewId_) beginPassLocked(*plan, light, started);
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
