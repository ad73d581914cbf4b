#include "master/LiveRenderer.h"

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <map>
#include <mutex>
#include <thread>

#include "master/FrameRenderer.h"
#include "parse/SceneLoader.h"

namespace prism {
namespace {

// Records what the renderer reports; waits are bounded.
class Recorder : public LiveListener {
 public:
  void passStarted(const PassInfo& pass) override {
    const std::lock_guard<std::mutex> lock(mutex_);
    passes_.push_back(pass);
    current_ = pass.frame;
    changed_.notify_all();
    images_[pass.frame] = ImageRgb(pass.view->width, pass.view->height);
  }
  void tileAssigned(uint32_t, uint32_t, int) override {}
  void tileFinished(uint32_t frame, std::shared_ptr<const TileResult> tile, int) override {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (frame != current_) ++notCurrent_;  // must never happen: ended frames are dropped
    ++tilesSeen_;
    changed_.notify_all();
    ImageRgb& image = images_.at(frame);
    for (int y = 0; y < tile->rect.height; ++y) {
      for (int x = 0; x < tile->rect.width; ++x) {
        image.at(tile->rect.x + x, tile->rect.y + y) =
            tile->pixels[static_cast<size_t>(y) * tile->rect.width + x];
      }
    }
  }
  void passFinished(uint32_t frame, double) override {
    const std::lock_guard<std::mutex> lock(mutex_);
    finished_.push_back(frame);
    changed_.notify_all();
  }
  void statsUpdated(const LiveStats& stats) override {
    const std::lock_guard<std::mutex> lock(mutex_);
    stats_ = stats;
  }

  bool waitForFinished(size_t count) {
    std::unique_lock<std::mutex> lock(mutex_);
    return changed_.wait_for(lock, std::chrono::seconds(30),
                             [&] { return finished_.size() >= count; });
  }
  bool waitForPasses(size_t count) {
    std::unique_lock<std::mutex> lock(mutex_);
    return changed_.wait_for(lock, std::chrono::seconds(30),
                             [&] { return passes_.size() >= count; });
  }
  bool waitForTiles(size_t count) {
    std::unique_lock<std::mutex> lock(mutex_);
    return changed_.wait_for(lock, std::chrono::seconds(30), [&] { return tilesSeen_ >= count; });
  }
  size_t notCurrent() {
    const std::lock_guard<std::mutex> lock(mutex_);
    return notCurrent_;
  }
  std::vector<PassInfo> passes() {
    const std::lock_guard<std::mutex> lock(mutex_);
    return passes_;
  }
  ImageRgb image(uint32_t frame) {
    const std::lock_guard<std::mutex> lock(mutex_);
    return images_.at(frame);
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<PassInfo> passes_;
  std::vector<uint32_t> finished_;
  std::map<uint32_t, ImageRgb> images_;
  LiveStats stats_;
  uint32_t current_ = 0;
  size_t notCurrent_ = 0;
  size_t tilesSeen_ = 0;
};

SceneDescription smallDefaultScene() {
  SceneDescription d = loadScene(PRISM_SOURCE_DIR "/scenes/default.yaml");
  d.render.width = 80;
  d.render.height = 44;
  d.render.samplesPerPixel = 2;
  return d;
}

TEST(LiveRenderer, PreviewThenFullPassesEachAFrameAndPassOneIsTheRenderedImage) {
  const SceneDescription d = smallDefaultScene();
  const Scene scene(d);
  LiveOptions options;
  options.threads = 2;
  options.previewScale = 4;
  options.maxPasses = 2;
  LiveRenderer renderer(scene, options);
  Recorder recorder;
  std::thread coordinator([&] { renderer.run(recorder); });
  renderer.setView({d.camera, d.render.samplesPerPixel, DebugView::Image});
  ASSERT_TRUE(recorder.waitForFinished(3));
  renderer.stop();
  coordinator.join();

  const std::vector<PassInfo> passes = recorder.passes();
  ASSERT_EQ(passes.size(), 3u);  // preview, pass 1, pass 2, then idle
  EXPECT_EQ(passes[0].pass, 0);
  EXPECT_EQ(passes[0].view->width, 20);
  EXPECT_EQ(passes[0].view->height, 11);
  EXPECT_EQ(passes[0].view->samplesPerPixel, 1);
  EXPECT_EQ(passes[1].pass, 1);
  EXPECT_EQ(passes[1].view->width, 80);
  EXPECT_EQ(passes[2].view->seed, LiveRenderer::passSeed(d.render.seed, 2));
  EXPECT_NE(passes[2].view->seed, d.render.seed);
  EXPECT_LT(passes[0].frame, passes[1].frame);
  EXPECT_LT(passes[1].frame, passes[2].frame);

  const ImageRgb expected = renderFrame(scene, FrameOptions{}).image;
  const ImageRgb pass1 = recorder.image(passes[1].frame);
  ASSERT_EQ(pass1.pixels.size(), expected.pixels.size());
  for (size_t i = 0; i < expected.pixels.size(); ++i) {
    ASSERT_EQ(pass1.pixels[i], expected.pixels[i]) << "pixel " << i;
  }
  const ImageRgb pass2 = recorder.image(passes[2].frame);
  size_t differing = 0;  // its own seed: other samples
  for (size_t i = 0; i < expected.pixels.size(); ++i)
    differing += pass2.pixels[i] != pass1.pixels[i];
  EXPECT_GT(differing, expected.pixels.size() / 10);

  const LiveStats stats = renderer.stats();
  ASSERT_EQ(stats.ranks.size(), 1u);
  EXPECT_EQ(stats.ranks[0].threads, 2);
  size_t tiles = 0;
  for (const PassInfo& p : passes) tiles += p.tiles.size();
  EXPECT_EQ(stats.ranks[0].tiles, tiles);
  EXPECT_EQ(stats.passesDone, 2);
  EXPECT_EQ(recorder.notCurrent(), 0u);
}

TEST(LiveRenderer, ANewViewEndsTheFrameAndItsLateTilesAreDropped) {
  const SceneDescription d = smallDefaultScene();
  const Scene scene(d);
  LiveOptions options;
  options.threads = 2;
  options.previewScale = 1;  // straight to full passes
  options.maxPasses = 1;
  options.tileSize = 8;
  LiveRenderer renderer(scene, options);
  Recorder recorder;
  std::thread coordinator([&] { renderer.run(recorder); });
  renderer.setView({d.camera, 64, DebugView::Image});  // slow: about a second
  ASSERT_TRUE(recorder.waitForTiles(2));               // the threads are on their next tiles now
  CameraDesc moved = d.camera;
  moved.position.x += 1.0f;
  renderer.setView({moved, 1, DebugView::Normals});
  ASSERT_TRUE(recorder.waitForFinished(1));
  renderer.stop();
  coordinator.join();

  const std::vector<PassInfo> passes = recorder.passes();
  ASSERT_EQ(passes.size(), 2u);
  EXPECT_EQ(passes[1].view->camera.position, moved.position);
  EXPECT_EQ(passes[1].view->debugView, DebugView::Normals);
  EXPECT_GT(passes[1].frame, passes[0].frame);
  // The first frame never finished; the tiles its threads were rendering at the switch came
  // back late and were dropped, never passed on as tiles of the new frame.
  EXPECT_EQ(recorder.notCurrent(), 0u);
  const LiveStats stats = renderer.stats();
  EXPECT_GE(stats.ranks[0].staleTiles, 1u);
  EXPECT_LT(stats.ranks[0].tiles, passes[0].tiles.size() + passes[1].tiles.size());
  EXPECT_EQ(stats.viewId, 2u);
}

}  // namespace
}  // namespace prism
