// The render threads' side of a frame that ends: a tile of an ended frame (TileJob::frameEnded),
// ended before it is taken or while it is rendered, stops after its current row and gives no
// result, and the thread goes on with the next job.
#include "cluster/TileWorkerPool.h"

#include <gtest/gtest.h>

#include <chrono>
#include <deque>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "parse/SceneLoader.h"

namespace prism {
namespace {

SceneDescription smallScene(int samples) {
  SceneDescription d = loadScene(PRISM_SOURCE_DIR "/scenes/default.yaml");
  d.render.width = 64;
  d.render.height = 48;
  d.render.samplesPerPixel = samples;
  return d;
}

// Seconds for one thread to render the whole 64×48 tile of scene.
double wholeTileSeconds(const Scene& scene) {
  TileWorkerPool pool(scene, ThreadCount::resolve(1));
  bool taken = false;
  const auto start = std::chrono::steady_clock::now();
  pool.start(
      [&]() -> std::optional<TileJob> {
        if (taken) return std::nullopt;
        taken = true;
        return TileJob(0, {0, 0, 64, 48}, 1);
      },
      [](const TileJob&, TileResult&&) {});
  pool.join();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

TEST(TileWorkerPool, ATileOfAnEndedFrameGivesNoResultAndTheThreadTakesTheNext) {
  // A whole 64×48 frame at 4096 spp as one tile takes seconds; one row of it a small part. The
  // slow path, timed here: the whole tile, projected from the same tile at a 64th of the samples.
  const double wholeTile = 64 * wholeTileSeconds(Scene(smallScene(4096 / 64)));
  const Scene scene(smallScene(4096));
  auto endedBefore = std::make_shared<std::atomic<bool>>(true);  // before the tile is taken
  auto endedDuring = std::make_shared<std::atomic<bool>>(false);
  std::deque<TileJob> jobs;
  TileJob heavy(0, {0, 0, 64, 48}, 1);
  heavy.frameEnded = endedBefore;
  jobs.push_back(heavy);
  heavy.frame = 2;
  heavy.frameEnded = endedDuring;
  jobs.push_back(heavy);
  jobs.push_back(TileJob(1, {0, 0, 8, 2}, 3));  // another frame's small tile
  std::mutex mutex;
  std::vector<uint32_t> delivered;
  TileWorkerPool pool(scene, ThreadCount::resolve(1));
  pool.start(
      [&]() -> std::optional<TileJob> {
        const std::lock_guard<std::mutex> lock(mutex);
        if (jobs.empty()) return std::nullopt;
        TileJob job = jobs.front();
        jobs.pop_front();
        return job;
      },
      [&](const TileJob& job, TileResult&& tile) {
        const std::lock_guard<std::mutex> lock(mutex);
        EXPECT_EQ(tile.pixels.size(), static_cast<size_t>(job.rect.pixelCount()));
        delivered.push_back(job.frame);
      });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  *endedDuring = true;  // the second heavy tile is being rendered
  const auto ended = std::chrono::steady_clock::now();
  pool.join();
  const double afterTheEnd =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - ended).count();
  EXPECT_EQ(delivered, std::vector<uint32_t>{3});  // the ended frames' tiles never came
  // No row of the first and the rest of a row of the second (64 × 2 pixels at 4096 spp), not
  // the rest of a whole tile's 24 rows (about 6 s here).
  EXPECT_LT(afterTheEnd, wholeTile / 4) << "a whole tile takes " << wholeTile << " s";
}

}  // namespace
}  // namespace prism
