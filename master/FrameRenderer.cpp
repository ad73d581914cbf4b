#include "master/FrameRenderer.h"

#include <atomic>
#include <chrono>

#include "master/Framebuffer.h"
#include "master/TilePlan.h"
#include "slave/TileWorkerPool.h"

namespace prism {

FrameResult renderFrame(const Scene& scene, const FrameOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const RenderSettings& settings = scene.settings();
  const TileWorkerPool pool(scene, options.threads);

  FrameResult result;
  result.threads = pool.threadCount();
  result.tileSize = options.tileSize > 0
                        ? options.tileSize
                        : automaticTileSize(settings.width, settings.height, pool.threadCount());
  const std::vector<TileRect> rects = planTiles(settings.width, settings.height, result.tileSize);
  std::vector<TileJob> jobs;
  jobs.reserve(rects.size());
  for (uint32_t i = 0; i < rects.size(); ++i) jobs.push_back({i, rects[i]});
  result.tileCount = jobs.size();

  Framebuffer framebuffer(settings.width, settings.height, jobs.size());
  std::atomic<size_t> done{0};
  pool.renderAll(
      jobs,
      [&](TileResult&& tile) {
        result.rays += tile.rays;
        result.busyThreadSeconds += tile.seconds;
        framebuffer.insert(tile);
        ++done;
      },
      [&] {
        if (options.progress) options.progress(done.load(), jobs.size());
      });
  if (options.progress) options.progress(jobs.size(), jobs.size());

  result.image = framebuffer.image();
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace prism
