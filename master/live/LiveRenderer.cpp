#include "master/live/LiveRenderer.h"

#include <algorithm>
#include <stdexcept>

#include "caustics/CausticMapMemory.h"
#include "caustics/GatherRadius.h"
#include "image/DisplayBytes.h"
#include "master/frame/TilePlan.h"
#include "master/live/LivePassPlan.h"
#include "math/Random.h"
#include "util/Percentile.h"

namespace prism {

struct LiveRenderer::Event {
  enum class Kind { Started, Assigned, Finished, PassFinished } kind;
  uint32_t frame = 0;
  uint32_t tile = 0;
  int rank = 0;
  std::shared_ptr<const TileResult> result;
  double seconds = 0.0;
  PassInfo info;  // Started
};

struct LiveRenderer::Pass {
  PassInfo info;
  std::vector<bool> assigned;  // per tile: handed out at least once
  size_t assignedCount = 0;
  size_t done = 0;
  bool finished = false;
  bool announced = false;  // the listener has heard of its start
  double started = 0.0;
  double seconds = 0.0;  // start to end
  double busySeconds = 0.0;
  std::deque<Event> events;  // for the listener, in order

  Pass(PassInfo i, double now)
      : info(std::move(i)), assigned(info.tiles.size(), false), started(now) {}
  bool allAssigned() const { return assignedCount == assigned.size(); }
};

namespace {

constexpr size_t kFrameTimeWindow = 60;  // frames the frame-time statistics cover

// Tile news (a tile handed out, a tile finished) reach the listener in batches: the first of a
// batch waits up to this long for company, half a display refresh. Told one by one they woke
// the coordinator and the window twice a tile, and on a machine whose cores all render each
// wake-up preempts a render thread. A pass's end, and a pass's last tile handed out (the next
// pass may start), are told at once.
constexpr double kNewsDelay = 0.008;

// Whether the view's refinement passes trace a photon pass first.
bool tracesPhotons(const ViewSettings& view) {
  return view.caustics == CausticMethod::PhotonMap && view.debugView == DebugView::Image;
}

}  // namespace

uint64_t LiveRenderer::passSeed(uint64_t sceneSeed, int pass) {
  if (pass <= 1) return sceneSeed;
  return mix64(sceneSeed ^ mix64(static_cast<uint64_t>(pass) * 0x9e3779b97f4a7c15ULL));
}

LiveRenderer::LiveRenderer(const Scene& scene, const LiveOptions& options, Transport* cluster)
    : LiveRenderer(std::make_unique<WorkDispatcher>(scene, cluster, options.distribution), nullptr,
                   options) {}

LiveRenderer::LiveRenderer(WorkDispatcher& dispatcher, const LiveOptions& options)
    : LiveRenderer(nullptr, &dispatcher, options) {}

LiveRenderer::LiveRenderer(std::unique_ptr<WorkDispatcher> own, WorkDispatcher* dispatcher,
                           const LiveOptions& options)
    : ownDispatcher_(std::move(own)),
      dispatcher_(dispatcher ? *dispatcher : *ownDispatcher_),
      link_(dispatcher_.link()),
      scene_(dispatcher_.scene()),
      options_(options),
      start_(SteadyClock::now()),
      governor_(options.frameTimeSeconds, options.previewScale),
      lastStats_(start_),
      maxRadius_(scene_.causticSettings().maxRadius > 0.0f ? scene_.causticSettings().maxRadius
                                                           : automaticMaxRadius(scene_)),
      mapsRefusal_(prism::causticMapsRefusal(scene_, options.memoryLimit)) {}

LiveRenderer::~LiveRenderer() {
  stop();
  try {
    dispatcher_.join();  // before the members its threads report to are gone
  } catch (...) {        // run() has rethrown a render thread's failure already
  }
}

void LiveRenderer::setView(const ViewSettings& view) {
  std::vector<uint32_t> stale;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    pendingView_ = view;
    pendingSince_ = SteadyClock::now();
    // Refinement passes of the view being left end now; a view's first frame is finished: it is
    // what shows the move, within about one frame time.
    for (auto it = passes_.begin(); it != passes_.end();) {
      if ((*it)->info.firstOfView) {
        ++it;
        continue;
      }
      stale.push_back((*it)->info.frame);
      it = passes_.erase(it);
    }
    cancelPhotons_ = true;  // a photon pass being traced for the old view is dropped
  }
  // Their tiles are stale from now on. By frame id: the coordinator may have begun a pass of the
  // new view since the lock was released, and that one must run.
  for (uint32_t frame : stale) dispatcher_.endFrame(frame);
  changed_.notify_all();
  dispatcher_.wake();  // the coordinator may be waiting for slaves' messages or photons
}

void LiveRenderer::stop() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopped_ = true;
    cancelPhotons_ = true;  // run() returns without finishing a photon pass
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
  info.viewTag = plan.view.tag;
  info.pass = index;
  info.scale = plan.scale;
  info.firstOfView = plan.firstOfView;
  auto view = std::make_shared<RenderView>();
  view->camera = plan.view.camera;
  view->width = info.scale.side(settings.width);
  view->height = info.scale.side(settings.height);
  view->samplesPerPixel = index == 0 ? 1 : plan.view.samplesPerPixel;
  view->seed = passSeed(settings.seed, index);
  view->debugView = plan.view.debugView;
  view->jitterSingleSample = index >= 2;  // else every 1-spp pass would repeat pass 1
  view->causticMapBlur = plan.view.causticMapBlur;
  // A frame while moving is shown and replaced, never averaged: other ranks send it as the
  // bytes the window shows (3 a pixel, not 12), at the scene's exposure, the window's.
  if (index == 0 && displayBytesInvertible(settings.exposure)) {
    view->displayExposure = settings.exposure;
  }
  info.view = view;
  info.light = std::move(light);
  const int tileSize =
      options_.distribution.tileSize > 0
          ? std::max(8, info.scale.side(options_.distribution.tileSize))
          : streamedTileSize(view->width, view->height, view->samplesPerPixel, liveThreads);
  info.tiles = planTiles(view->width, view->height, tileSize);
  passes_.push_back(std::make_unique<Pass>(info, now()));
  live_.frame = info.frame;
  live_.viewId = info.viewId;
  live_.pass = info.pass;
  return info;
}

bool LiveRenderer::mayStartLocked() const {
  const int maxPasses =
      view_.maxPasses > 0 ? std::min(view_.maxPasses, options_.maxPasses) : options_.maxPasses;
  const bool refine = lastIndex_ >= 0 && lastIndex_ < maxPasses;
  if (!pendingView_ && !refine) return false;  // nothing to render
  size_t open = 0;
  const Pass* newest = nullptr;
  for (const std::unique_ptr<Pass>& p : passes_) {
    if (p->finished) continue;
    ++open;
    newest = p.get();
  }
  if (open == 0) return true;
  // Pipelined: the next frame's tiles are handed out once the current frame's all are. Not
  // behind a photon-mapped pass (a slave holds one photon map, and the next pass's would
  // replace it while a tile of this one could still be re-issued to it), nor for a pass that
  // traces photons first (the coordinator would trace while this frame's end waits).
  if (!options_.pipeline || open != 1 || !newest->allAssigned()) return false;
  const RenderPass* light = newest->info.light.get();
  if (light && light->source == CausticSource::PhotonMap) return false;
  return pendingView_ || !tracesPhotons(view_);
}

std::optional<LiveRenderer::PassPlan> LiveRenderer::nextPassLocked() {
  if (!mayStartLocked()) return std::nullopt;
  if (pendingView_) {
    view_ = *pendingView_;
    pendingView_.reset();
    if (view_.frameTimeSeconds >= 0.0) governor_.setTargetSeconds(view_.frameTimeSeconds);
    ++viewId_;
    viewSince_ = pendingSince_;
    live_.passesDone = 0;
    live_.previewLatencySeconds = 0.0;
    live_.firstFullSeconds = 0.0;
    live_.photons = {};
    live_.photons.method = view_.caustics;
    // The first frame of a view, at the resolution that meets the frame-time target and 1 spp.
    // At full resolution it is pass 1 when that is what pass 1 renders (the view's samples per
    // pixel, and no photon pass, which a moving camera would wait for) — in one process. With
    // slaves it stays a frame only shown (pass 0), whose tiles come as display bytes, a quarter
    // of radiance's: while the camera moves that is what the link carries, and when it stops
    // pass 1 follows one frame later.
    const RenderSettings& r = scene_.settings();
    const FrameScale scale = governor_.scaleFor(r.width, r.height);
    const bool isPassOne =
        scale.full() && view_.samplesPerPixel == 1 && !tracesPhotons(view_) && !link_.hasSlaves();
    lastIndex_ = isPassOne ? 1 : 0;
    return PassPlan{lastIndex_, nextFrame_++, viewId_, view_, scale, true};
  }
  ++lastIndex_;  // the still camera's next full-resolution pass
  cancelPhotons_ = false;
  return PassPlan{lastIndex_, nextFrame_++, viewId_, view_, FrameScale{}, false};
}

void LiveRenderer::frameFinishedLocked(const Pass& pass, double end) {
  // Frames overlap when pipelined: a frame's time starts when the one before it ended.
  const double seconds = end - std::max(pass.started, lastFrameEnd_);
  lastFrameEnd_ = end;
  const RenderView& v = *pass.info.view;
  // A photon-mapped pass costs its gathers, which frames while moving never make: its time
  // would predict them too slow, and the resolution would drop at the next move.
  const RenderPass* light = pass.info.light.get();
  if (!(light && light->source == CausticSource::PhotonMap)) {
    governor_.frameFinished(static_cast<uint64_t>(v.width) * static_cast<uint64_t>(v.height) *
                                static_cast<uint64_t>(v.samplesPerPixel),
                            seconds);
  }
  frameSeconds_.push_back(seconds);
  if (frameSeconds_.size() > kFrameTimeWindow) frameSeconds_.pop_front();
  FrameTimeStats& f = live_.frameTimes;
  f.shownWidth = v.width;
  f.shownHeight = v.height;
  if (pass.info.firstOfView) ++(pass.info.scale.full() ? f.fullResolutionFrames : f.reducedFrames);
}

LiveRenderer::Pass* LiveRenderer::findLocked(uint32_t frame) {
  for (const std::unique_ptr<Pass>& p : passes_) {
    if (p->info.frame == frame) return p.get();
  }
  return nullptr;
}

void LiveRenderer::tileAssigned(uint32_t frame, uint32_t tile, int rank) {
  bool wakeNow = false;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    Pass* p = findLocked(frame);
    if (!p) return;
    p->events.push_back({Event::Kind::Assigned, frame, tile, rank, nullptr, 0.0, {}});
    bool allAssigned = false;
    if (tile < p->assigned.size() && !p->assigned[tile]) {
      p->assigned[tile] = true;
      allAssigned = ++p->assignedCount == p->assigned.size();
    }
    // With all tiles handed out the coordinator queues the next frame now.
    wakeNow = newsQueuedLocked(allAssigned);
  }
  if (!wakeNow) return;
  changed_.notify_all();
  link_.wake();  // it may be waiting for the slaves' messages
}

bool LiveRenderer::wantsTiles(uint32_t frame) {
  const std::lock_guard<std::mutex> lock(mutex_);
  return findLocked(frame) != nullptr;
}

void LiveRenderer::tileFinished(uint32_t frame, TileResult&& tile, int rank) {
  if (!recordFinishedTile(frame, std::move(tile), rank)) return;
  changed_.notify_all();
  link_.wake();  // the coordinator may be waiting for the slaves' messages
}

bool LiveRenderer::recordFinishedTile(uint32_t frame, TileResult&& tile, int rank) {
  const std::lock_guard<std::mutex> lock(mutex_);
  // The dispatcher accepts only tiles of frames it still runs, and a pass that setView() drops
  // has its frame ended first; a pass may have been dropped in between, though.
  Pass* pass = findLocked(frame);
  if (!pass) return false;
  Pass& p = *pass;
  p.busySeconds += tile.seconds;
  const uint32_t index = tile.tileIndex;
  p.events.push_back({Event::Kind::Finished,
                      frame,
                      index,
                      rank,
                      std::make_shared<const TileResult>(std::move(tile)),
                      0.0,
                      {}});
  if (++p.done == p.info.tiles.size()) {
    p.finished = true;
    const double end = now();
    p.seconds = end - p.started;
    frameFinishedLocked(p, end);
    const double sinceView = secondsSince(viewSince_);
    if (p.info.firstOfView) live_.previewLatencySeconds = sinceView;
    if (p.info.pass >= 1) {
      ++live_.passesDone;
      live_.lastPassSeconds = p.seconds;
      live_.lastPassBusySeconds = p.busySeconds;
      if (p.info.pass == 1) live_.firstFullSeconds = sinceView;
    }
  }
  return newsQueuedLocked(p.finished);
}

void LiveRenderer::takeDeliveriesLocked(std::vector<Event>& out) {
  // In pass order: a later pass's news waits until the listener has heard the one before end.
  while (!passes_.empty()) {
    Pass& p = *passes_.front();
    if (!p.announced) {
      p.announced = true;
      Event started{Event::Kind::Started, p.info.frame, 0, 0, nullptr, 0.0, p.info};
      out.push_back(std::move(started));
    }
    for (Event& e : p.events) out.push_back(std::move(e));
    p.events.clear();
    if (!p.finished) return;
    out.push_back({Event::Kind::PassFinished, p.info.frame, 0, 0, nullptr, p.seconds, {}});
    passes_.pop_front();
  }
}

void LiveRenderer::takeDueDeliveriesLocked(std::vector<Event>& out) {
  if (!newsDueLocked()) return;
  takeDeliveriesLocked(out);
  // News left behind belong to a pass after one still running, and follow that one's end,
  // which is urgent news of its own.
  newsSince_ = -1.0;
  newsUrgent_ = false;
}

bool LiveRenderer::newsQueuedLocked(bool urgent) {
  const bool first = newsSince_ < 0.0;
  if (first) newsSince_ = now();
  newsUrgent_ = newsUrgent_ || urgent;
  // The first news of a batch wakes the coordinator too: it then sleeps until the batch is due.
  return urgent || first;
}

bool LiveRenderer::newsDueLocked() const {
  if (passes_.empty()) return false;
  if (!passes_.front()->announced) return true;  // a pass begins: the listener hears it at once
  if (newsUrgent_) return true;
  return newsSince_ >= 0.0 && now() - newsSince_ >= kNewsDelay;
}

double LiveRenderer::untilNewsDueLocked(double bound) const {
  if (bound <= 0.0 || newsDueLocked()) return 0.0;
  if (newsSince_ < 0.0) return bound;
  return std::clamp(newsSince_ + kNewsDelay - now(), 0.0, bound);
}

LiveStats LiveRenderer::statsLocked(double elapsedSeconds, std::vector<RankStats> ranks) {
  LiveStats s = live_;
  s.ranks = std::move(ranks);
  RayCounters total;
  s.totalThreads = 0;
  for (const RankStats& r : s.ranks) {
    total += r.rays;
    if (!r.retired) s.totalThreads += r.threads;
  }
  s.raysPerSecond = static_cast<double>(total.total() - raysAtLastStats_.total()) /
                    std::max(elapsedSeconds, 1e-3);
  raysAtLastStats_ = total;
  FrameTimeStats& f = s.frameTimes;
  const std::vector<double> times(frameSeconds_.begin(), frameSeconds_.end());
  f.frames = static_cast<int>(times.size());
  f.medianSeconds = percentile(times, 0.5);
  f.p95Seconds = percentile(times, 0.95);
  double sum = 0.0;
  for (double t : times) sum += t;
  f.framesPerSecond = sum > 0.0 ? static_cast<double>(times.size()) / sum : 0.0;
  s.frameTimeTargetSeconds = governor_.targetSeconds();
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
      std::vector<Event> events;
      std::optional<PassPlan> plan;
      const int liveThreads = dispatcher_.liveThreads();  // the dispatcher's lock: before ours
      {
        const std::lock_guard<std::mutex> lock(mutex_);
        if (stopped_ || dispatcher_.localFailed()) break;
        plan = nextPassLocked();
        takeDueDeliveriesLocked(events);
      }
      // The news first: a photon pass traced below must not hold up the frame before it.
      for (Event& e : events) {
        switch (e.kind) {
          case Event::Kind::Started:
            listener.passStarted(e.info);
            break;
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
      if (plan) {
        // Photons are traced here, without the lock: the GUI thread can still ask for views.
        std::shared_ptr<const RenderPass> light = passLight(*plan);
        {
          const std::lock_guard<std::mutex> lock(mutex_);
          // A view asked for meanwhile wins; this pass is dropped before it starts.
          if (!pendingView_ && plan->viewId == viewId_) {
            started = beginPassLocked(*plan, light, liveThreads);
          }
        }
        if (started) {
          FramePlan frame;
          frame.frame = started->frame;
          frame.tiles = started->tiles;
          frame.view = started->view;
          frame.light = started->light;
          frame.schedule = options_.distribution.schedule;
          // Queued behind the frame still running, which the listener hears of first.
          dispatcher_.queueFrame(frame, this);
        }
      }
      if (started) continue;  // its first tiles may be news already; the next frame may be due
      // A view, a stop, a frame finished or handed out, or a batch of tile news begun wakes this
      // wait; it lasts until the batch is due, and is bounded for the statistics.
      constexpr double kStatsBound = 0.05;
      if (link_.hasSlaves()) {
        double wait = 0.0;
        {
          const std::lock_guard<std::mutex> lock(mutex_);
          wait = untilNewsDueLocked(kStatsBound);
        }
        dispatcher_.service(wait);
      } else {
        std::unique_lock<std::mutex> lock(mutex_);
        const double end = now() + kStatsBound;
        while (!(stopped_ || newsDueLocked() || mayStartLocked())) {
          const double wait = untilNewsDueLocked(end - now());
          if (wait <= 0.0) break;
          changed_.wait_for(lock, std::chrono::duration<double>(wait));
        }
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
