#include "master/runtime/FrameRenderer.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <thread>

#include "master/runtime/Framebuffer.h"
#include "master/runtime/TileDispatcher.h"
#include "master/runtime/TilePlan.h"

namespace prism {
namespace {

// Puts the frame's accepted tiles into the image.
class FrameAssembly final : public FrameListener {
 public:
  FrameAssembly(int width, int height, size_t tiles)
      : framebuffer_(width, height, tiles), tileSeconds_(tiles, 0.0) {}

  void tileFinished(uint32_t, TileResult&& tile, int) override {
    tileSeconds_[tile.tileIndex] = tile.seconds;
    framebuffer_.insert(tile);
  }

  // Only after the dispatcher's threads have stopped.
  Framebuffer& framebuffer() { return framebuffer_; }
  const std::vector<double>& tileSeconds() const { return tileSeconds_; }

 private:
  Framebuffer framebuffer_;
  std::vector<double> tileSeconds_;
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

}  // namespace

FrameResult renderFrame(const Scene& scene, const FrameOptions& options, SlaveLink& link) {
  const auto start = SteadyClock::now();
  const RenderSettings& settings = scene.settings();
  TileDispatcher dispatcher(scene, link, options.distribution);

  FrameResult result;
  result.threads = options.masterRenders ? dispatcher.localThreads() : 0;
  result.tileSize = options.distribution.tileSize > 0
                        ? options.distribution.tileSize
                        : automaticTileSize(settings.width, settings.height,
                                            dispatcher.localThreads() * link.ranks());
  const std::vector<TileRect> rects = planTiles(settings.width, settings.height, result.tileSize);
  result.tileCount = rects.size();

  FrameAssembly assembly(settings.width, settings.height, rects.size());
  dispatcher.beginFrame(
      {options.frameId, rects, nullptr, options.pass, options.masterRenders, options.activeSlaves},
      &assembly);
  if (options.masterRenders) dispatcher.startLocalWorkers();

  try {
    auto lastProgress = SteadyClock::now();
    while (!dispatcher.frameComplete()) {
      if (dispatcher.localFailed()) break;  // join() below rethrows the thread's exception
      if (options.stopRequested && options.stopRequested()) {
        result.interrupted = true;
        dispatcher.cancel();
        break;
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
        break;
      }
      if (options.progress && secondsSince(lastProgress) > 0.1) {
        options.progress(dispatcher.tilesDone(), rects.size());
        lastProgress = SteadyClock::now();
      }
    }
  } catch (...) {
    dispatcher.stop();
    dispatcher.join();
    throw;
  }
  dispatcher.stop();
  dispatcher.join();
  if (options.progress && !result.interrupted) options.progress(rects.size(), rects.size());

  result.tileDone = assembly.framebuffer().received();
  result.image = assembly.framebuffer().takeImage();
  result.workers = dispatcher.stats();
  result.tiles = rects;
  result.tileSeconds = assembly.tileSeconds();
  result.reissuedTiles = dispatcher.reissuedTiles();
  for (const RankStats& w : result.workers) {
    result.rays += w.rays;
    result.busyThreadSeconds += w.busySeconds;
  }
  result.seconds = secondsSince(start);
  return result;
}

FrameResult renderFrame(const Scene& scene, const FrameOptions& options) {
  SlaveLink alone(nullptr, options.distribution);
  return renderFrame(scene, options, alone);
}

size_t FrameResult::tilesDone() const {
  return static_cast<size_t>(std::count(tileDone.begin(), tileDone.end(), true));
}

}  // namespace prism
