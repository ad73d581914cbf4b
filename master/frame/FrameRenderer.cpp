#include "master/frame/FrameRenderer.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <thread>

#include "master/dispatch/WorkDispatcher.h"
#include "master/frame/Framebuffer.h"
#include "master/frame/TilePlan.h"

namespace prism {
namespace {

// Puts the frame's accepted tiles into the image.
class FrameAssembly final : public FrameListener {
 public:
  FrameAssembly(int width, int height, size_t tiles)
      : framebuffer_(width, height, tiles), tileSeconds_(tiles, 0.0) {}

  void tileFinished(uint32_t, TileResult&& tile, int) override {
    if (!firstTileAt_) firstTileAt_ = SteadyClock::now();
    tileSeconds_[tile.tileIndex] = tile.seconds;
    framebuffer_.insert(tile);
  }

  // Only once the frame has ended (WorkDispatcher::endFrame): no tile is accepted into it then.
  Framebuffer& framebuffer() { return framebuffer_; }
  const std::vector<double>& tileSeconds() const { return tileSeconds_; }
  std::optional<SteadyClock::time_point> firstTileAt() const { return firstTileAt_; }

 private:
  Framebuffer framebuffer_;
  std::vector<double> tileSeconds_;
  std::optional<SteadyClock::time_point> firstTileAt_;
};

// Whether a stop is requested within a moment (kStopGraceSeconds): a slave's failure that
// comes with a stop of this rank (every rank signalled together) belongs to the stop.
constexpr double kStopGraceSeconds = 0.5;
bool stopFollows(const FrameOptions& options) {
  if (!options.stopRequested) return false;
  const auto start = SteadyClock::now();
  while (!options.stopRequested()) {
    if (secondsSince(start) > kStopGraceSeconds) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

// What each rank did between two snapshots of the roster: its counts' difference, its facts
// as they are now.
std::vector<RankStats> rosterSince(std::vector<RankStats> now,
                                   const std::vector<RankStats>& before) {
  for (size_t r = 0; r < now.size() && r < before.size(); ++r) now[r] -= before[r];
  return now;
}

// Runs the frame's coordinating loop until it completes, is stopped, or fails.
void coordinateFrame(WorkDispatcher& dispatcher, const FrameOptions& options, size_t tileCount,
                     FrameResult& result) {
  auto lastProgress = SteadyClock::now();
  while (!dispatcher.frameComplete()) {
    if (dispatcher.localFailed()) {
      dispatcher.stop();
      dispatcher.join();  // rethrows the render thread's exception
    }
    if (options.stopRequested && options.stopRequested()) {
      result.interrupted = true;
      dispatcher.cancel();
      return;
    }
    // Every tile that finishes, here or on a slave, wakes this wait; the bound is for the
    // progress bar, a stop request and the slaves' silence.
    try {
      dispatcher.service(0.1);
    } catch (const std::runtime_error&) {
      // mpiexec signals every rank at once: a slave's "stopped by SIGTERM" may arrive before
      // this rank's own signal is seen. Then it is part of the stop, not a failure.
      if (!stopFollows(options)) throw;
      result.interrupted = true;
      dispatcher.cancel();
      return;
    }
    if (options.progress && secondsSince(lastProgress) > 0.1) {
      options.progress(dispatcher.tilesDone(), tileCount);
      lastProgress = SteadyClock::now();
    }
  }
}

}  // namespace

FrameResult renderFrame(WorkDispatcher& dispatcher, const FrameOptions& options) {
  const auto start = SteadyClock::now();
  const RenderSettings& settings = dispatcher.scene().settings();
  const std::vector<RankStats> rosterBefore = dispatcher.stats();
  const size_t reissuedBefore = dispatcher.reissuedTiles();

  FrameResult result;
  result.threads = options.masterRenders ? dispatcher.localThreads() : 0;
  result.tileSize = options.distribution.tileSize > 0
                        ? options.distribution.tileSize
                        : automaticTileSize(settings.width, settings.height,
                                            dispatcher.localThreads() * dispatcher.link().ranks());
  const std::vector<TileRect> rects = planTiles(settings.width, settings.height, result.tileSize);
  result.tileCount = rects.size();

  FrameAssembly assembly(settings.width, settings.height, rects.size());
  FramePlan plan{options.frameId,
                 rects,
                 nullptr,
                 options.pass,
                 options.masterRenders,
                 options.activeSlaves,
                 options.distribution.schedule};
  // Rank 0's threads first: they wait for the frame, and render while the dispatcher's opening
  // broadcast (if any) runs in beginFrame.
  if (options.masterRenders) dispatcher.startLocalWorkers();
  dispatcher.beginFrame(std::move(plan), &assembly);
  try {
    coordinateFrame(dispatcher, options, rects.size(), result);
  } catch (...) {
    dispatcher.endFrame(options.frameId);  // the assembly goes: nothing may report to it
    throw;
  }
  // Complete, or stopped: no tile of it is handed out or accepted any more.
  dispatcher.endFrame(options.frameId);
  if (options.progress && !result.interrupted) options.progress(rects.size(), rects.size());

  result.tileDone = assembly.framebuffer().received();
  result.image = assembly.framebuffer().takeImage();
  result.workers = rosterSince(dispatcher.stats(), rosterBefore);
  result.tiles = rects;
  result.tileSeconds = assembly.tileSeconds();
  result.firstTileAt = assembly.firstTileAt();
  result.reissuedTiles = dispatcher.reissuedTiles() - reissuedBefore;
  for (const RankStats& w : result.workers) {
    result.rays += w.rays;
    result.busyThreadSeconds += w.busySeconds;
  }
  result.seconds = secondsSince(start);
  return result;
}

FrameResult renderFrame(const Scene& scene, const FrameOptions& options) {
  WorkDispatcher alone(scene, nullptr, options.distribution);
  return renderFrame(alone, options);
}

size_t FrameResult::tilesDone() const {
  return static_cast<size_t>(std::count(tileDone.begin(), tileDone.end(), true));
}

}  // namespace prism
