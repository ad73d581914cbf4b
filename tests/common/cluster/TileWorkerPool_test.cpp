// The render threads' side of a frame that ends: a tile of an ended frame (TileJob::frameEnded),
// ended before it is taken or while it is rendered, stops after its current row and gives no
// result, and the thread goes on with the next job.
#include "cluster/TileWorkerPool.h"

#include <gtest/gtest.h>

#include <chrono>
#include <deque>
#include <mutex>
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

TEST(TileWorkerPool, ATileOfAnEndedFrameGivesNoResultAndTheThreadTakesTheNext) {
  // A whole 64×48 frame at 4096 spp as one tile takes seconds; one row of it a small part.
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
  const auto start = std::chrono::steady_clock::now();
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
  pool.join();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(delivered, std::vector<uint32_t>{3});  // the ended frames' tiles never came
  // No row of the first and a few of the second (64 × 2 pixels at 4096 spp each), not a whole
  // tile's 24 rows (about 6 s here).
  EXPECT_LT(seconds, 3.0);
}

}  // namespace
}  // namespace prism
