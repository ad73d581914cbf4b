#include "master/LiveRenderer.h"

#include <algorithm>
#include <stdexcept>

#include "caustics/PhotonGather.h"
#include "master/CausticPasses.h"
#include "master/PhotonPass.h"
#include "master/TilePlan.h"
#include "math/Random.h"

namespace prism {

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
  size_t done = 0;
  bool finished = false;
  double started = 0.0;
  double busySeconds = 0.0;

  Pass(PassInfo i, double now) : info(std::move(i)), started(now) {}
};

uint64_t LiveRenderer::passSeed(uint64_t sceneSeed, int pass) {
  if (pass <= 1) return sceneSeed;
  return mix64(sceneSeed ^ mix64(static_cast<uint64_t>(pass) * 0x9e3779b97f4a7c15ULL));
}

LiveRenderer::LiveRenderer(const Scene& scene, const LiveOptions& options, Transport* cluster)
    : scene_(scene),
      options_(options),
      link_(cluster, options.distribution),
      dispatcher_(scene, link_, options.distribution),
      start_(SteadyClock::now()),
      lastStats_(start_),
      maxRadius_(scene.causticSettings().maxRadius > 0.0f ? scene.causticSettings().maxRadius
                                                          : automaticMaxRadius(scene)) {}

LiveRenderer::~LiveRenderer() {
  stop();
  try {
    dispatcher_.join();  // before the members its threads report to are gone
  } catch (...) {        // run() has rethrown a render thread's failure already
  }
}

void LiveRenderer::setView(const ViewSettings& view) {
  std::optional<uint32_t> stale;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    pendingView_ = view;
    pendingSince_ = SteadyClock::now();
    if (pass_) stale = pass_->info.frame;
  }
  // The old view's tiles are stale from now on. By frame id: the coordinator may have begun a
  // pass of the new view since the lock was released, and that one must run.
  if (stale) dispatcher_.endFrame(*stale);
  changed_.notify_all();
  dispatcher_.wake();  // the coordinator may be waiting for slaves' messages
}

void LiveRenderer::stop() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopped_ = true;
  }
  dispatcher_.stop();
  changed_.notify_all();
}

PassInfo LiveRenderer::beginPassLocked(const PassPlan& plan,
                                       std::shared_ptr<const RenderPass> light, int liveThreads) {
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
  const int tileSize = options_.distribution.tileSize > 0
                           ? std::max(8, options_.distribution.tileSize / info.scale)
                           : automaticTileSize(view->width, view->height, liveThreads);
  info.tiles = planTiles(view->width, view->height, tileSize);
  pass_ = std::make_unique<Pass>(info, now());
  return info;
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
        scene_, causticMapSettings(scene_.causticSettings(), blur), dispatcher_.localThreads());
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
  PhotonPassStats p;
  auto map = tracePhotonPass(*tracer_, plan.frame, dispatcher_.localThreads(), link_, p);
  const PhotonGatherSettings gather =
      progressiveGather(c, maxRadius_, static_cast<int>(plan.index), gather_);
  gather_ = gather;
  sendPhotonMap(*map, plan.frame, gather, link_, p);

  const std::lock_guard<std::mutex> lock(mutex_);
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
    s.radius = gather.radius * gather.radiusScale;  // per-photon radii: their cap
  }
  return std::make_shared<const RenderPass>(RenderPass{
      plan.frame, true,
      std::make_shared<const PhotonGather>(std::move(map), gather, dispatcher_.localThreads())});
}

void LiveRenderer::tileAssigned(uint32_t frame, uint32_t tile, int rank) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    events_.push_back({Event::Kind::Assigned, frame, tile, rank, nullptr, 0.0});
  }
  changed_.notify_all();
}

void LiveRenderer::tileFinished(uint32_t frame, TileResult&& tile, int rank) {
  const std::lock_guard<std::mutex> lock(mutex_);
  // The dispatcher accepts only tiles of its current frame, which is this pass's: a view
  // change ends the frame before the pass is dropped.
  if (!pass_ || frame != pass_->info.frame) return;
  Pass& p = *pass_;
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

LiveStats LiveRenderer::statsLocked(double elapsedSeconds, std::vector<RankStats> ranks) {
  LiveStats s = live_;
  s.ranks = std::move(ranks);
  if (pass_) {
    s.frame = pass_->info.frame;
    s.viewId = pass_->info.viewId;
    s.pass = pass_->info.pass;
  }
  RayCounters total;
  s.totalThreads = 0;
  for (const RankStats& r : s.ranks) {
    total += r.rays;
    if (!r.retired) s.totalThreads += r.threads;
  }
  s.raysPerSecond = static_cast<double>(total.total() - raysAtLastStats_.total()) /
                    std::max(elapsedSeconds, 1e-3);
  raysAtLastStats_ = total;
  return s;
}

LiveStats LiveRenderer::stats() {
  std::vector<RankStats> ranks = dispatcher_.stats();  // before our lock: the lock order
  const std::lock_guard<std::mutex> lock(mutex_);
  const double elapsed = secondsSince(lastStats_);
  lastStats_ = SteadyClock::now();
  return statsLocked(elapsed, std::move(ranks));
}

void LiveRenderer::run(LiveListener& listener) {
  dispatcher_.startLocalWorkers();
  lastStats_ = SteadyClock::now();
  try {
    for (;;) {
      std::optional<PassInfo> started;
      std::deque<Event> events;
      std::optional<PassPlan> plan;
      {
        const std::lock_guard<std::mutex> lock(mutex_);
        if (stopped_ || dispatcher_.localFailed()) break;
        plan = nextPassLocked();
        events.swap(events_);
      }
      if (plan) {
        // Photons are traced here, without the lock: the GUI thread can still ask for views.
        std::shared_ptr<const RenderPass> light = passLight(*plan);
        const int liveThreads = dispatcher_.liveThreads();
        {
          const std::lock_guard<std::mutex> lock(mutex_);
          // A view asked for meanwhile wins; this pass is dropped before it starts.
          if (!pendingView_ && plan->viewId == viewId_) {
            started = beginPassLocked(*plan, light, liveThreads);
          }
        }
        if (started) {
          dispatcher_.beginFrame(
              {started->frame, started->tiles, started->view, started->light, true, -1}, this);
        }
      }
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
      if (started) listener.passStarted(*started);
      if (link_.hasSlaves()) {
        // A view, a stop or a finished tile wakes this wait; the bound is for the statistics.
        dispatcher_.service(0.05);
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
    dispatcher_.join();
    throw;
  }
  stop();
  dispatcher_.join();  // rethrows a render thread's failure
}

}  // namespace prism
