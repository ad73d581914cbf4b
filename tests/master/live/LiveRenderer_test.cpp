#include "master/live/LiveRenderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>

#include <cmath>
#include <cstring>

#include "HangGuard.h"
#include "caustics/CausticMapMemory.h"
#include "caustics/PhotonGather.h"
#include "image/DisplayBytes.h"
#include "master/RealSlave.h"
#include "master/ScriptedSlave.h"
#include "master/SlowPath.h"
#include "master/dispatch/SlaveShutdown.h"
#include "master/frame/CausticPasses.h"
#include "master/frame/FrameRenderer.h"
#include "master/frame/PhotonPass.h"
#include "parse/SceneLoader.h"
#include "render/TileRenderer.h"
#include "tests/common/caustics/BallOverFloorScene.h"
#include "transport/LoopbackTransport.h"

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
  // Until pass `pass` of view `viewId` has finished.
  bool waitForPass(uint64_t viewId, int pass) {
    std::unique_lock<std::mutex> lock(mutex_);
    return changed_.wait_for(lock, std::chrono::seconds(30), [&] {
      for (const PassInfo& p : passes_) {
        if (p.viewId == viewId && p.pass == pass &&
            std::find(finished_.begin(), finished_.end(), p.frame) != finished_.end()) {
          return true;
        }
      }
      return false;
    });
  }
  bool finished(uint32_t frame) {
    const std::lock_guard<std::mutex> lock(mutex_);
    return std::find(finished_.begin(), finished_.end(), frame) != finished_.end();
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

// Polls done() until it holds or `seconds` pass; whether it held.
bool waitUntil(const std::function<bool()>& done, double seconds = 30.0) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return true;
}

// Ends a run over the loopback: the renderer's numbers as it stands, then it stops and the
// slaves shut down cleanly.
LiveStats endLoopbackRun(LiveRenderer& renderer, std::thread& coordinator,
                         LoopbackNetwork& network) {
  const LiveStats stats = renderer.stats();
  renderer.stop();
  coordinator.join();
  std::ostringstream err;
  EXPECT_EQ(shutDownSlaves(&network.endpoint(0), 0, {}, err), 0) << err.str();
  return stats;
}

SceneDescription smallDefaultScene() {
  SceneDescription d = loadScene(PRISM_SOURCE_DIR "/scenes/default.yaml");
  d.render.width = 80;
  d.render.height = 44;
  d.render.samplesPerPixel = 1;
  return d;
}

// A renderer's options: render threads on rank 0, the moving frame's preview scale (1: full
// resolution), passes of a still camera.
LiveOptions liveOptions(int threads, int previewScale, int maxPasses) {
  LiveOptions options;
  options.distribution.threads = threads;
  options.previewScale = previewScale;
  options.maxPasses = maxPasses;
  return options;
}

// `prism render` of the scene from another camera.
ImageRgb renderedFrom(SceneDescription d, const CameraDesc& camera) {
  d.camera = camera;
  return renderFrame(Scene(d), FrameOptions{}).image;
}

bool sameImage(const ImageRgb& a, const ImageRgb& b) {
  return a.pixels.size() == b.pixels.size() &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Color)) == 0;
}

TEST(LiveRenderer, PreviewThenFullPassesEachAFrameAndPassOneIsTheRenderedImage) {
  const SceneDescription d = smallDefaultScene();
  const Scene scene(d);
  LiveOptions options = liveOptions(2, 4, 2);
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

TEST(LiveRenderer, ANewViewEndsARefinementPassAndStopsItsTilesMidTile) {
  const SceneDescription d = smallDefaultScene();
  const Scene scene(d);
  LiveOptions options = liveOptions(2, 1, 1);
  options.distribution.tileSize = 44;  // two tiles, one a thread
  // The slow path, timed here: pass 1's tiles rendered to their end on the same two threads,
  // projected from the same frame at a 64th of the samples.
  SceneDescription lighter = d;
  lighter.render.samplesPerPixel = 16384 / 64;
  const Scene lighterScene(lighter);
  FrameOptions sameTiles;
  sameTiles.distribution = options.distribution;
  const double wholeTiles = 64 * test::secondsOf([&] { renderFrame(lighterScene, sameTiles); });
  LiveRenderer renderer(scene, options);
  Recorder recorder;
  std::thread coordinator([&] { renderer.run(recorder); });
  // The view's first frame is 1 spp; its pass 1, 16384 spp, takes seconds a tile (about 15 s
  // here), a row of blocks a twentieth of that. Both threads are mid-tile when the view changes.
  renderer.setView({d.camera, 16384, DebugView::Image});
  ASSERT_TRUE(recorder.waitForPass(1, 0));
  ASSERT_TRUE(recorder.waitForPasses(2));
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  CameraDesc moved = d.camera;
  moved.position.x += 1.0f;
  const auto switched = std::chrono::steady_clock::now();
  renderer.setView({moved, 1, DebugView::Normals});
  ASSERT_TRUE(recorder.waitForPass(2, 1));
  const double secondsToNewFrame =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - switched).count();
  renderer.stop();
  coordinator.join();

  const std::vector<PassInfo> passes = recorder.passes();
  ASSERT_EQ(passes.size(), 3u);
  EXPECT_EQ(passes[0].pass, 0);  // the first frame: 1 spp, not averaged
  EXPECT_TRUE(passes[0].firstOfView);
  EXPECT_EQ(passes[0].view->samplesPerPixel, 1);
  EXPECT_EQ(passes[1].pass, 1);
  EXPECT_FALSE(passes[1].firstOfView);
  EXPECT_EQ(passes[1].view->samplesPerPixel, 16384);
  EXPECT_EQ(passes[2].view->camera.position, moved.position);
  EXPECT_EQ(passes[2].view->debugView, DebugView::Normals);
  EXPECT_EQ(passes[2].pass, 1);
  EXPECT_GT(passes[2].frame, passes[1].frame);
  // Pass 1 never finished: the tiles its threads were rendering at the switch stopped after
  // their row (the new frame did not wait for them) and never came back.
  EXPECT_TRUE(recorder.finished(passes[0].frame));
  EXPECT_FALSE(recorder.finished(passes[1].frame));
  // Tiles run to their end would keep the new frame waiting most of wholeTiles; stopped after
  // their row, it waits a twentieth.
  EXPECT_LT(secondsToNewFrame, wholeTiles / 4) << "the ended tiles take " << wholeTiles << " s";
  EXPECT_EQ(recorder.notCurrent(), 0u);
  const LiveStats stats = renderer.stats();
  EXPECT_EQ(stats.ranks[0].staleTiles, 0u);
  EXPECT_EQ(stats.viewId, 2u);
}

// A view's first frame is what shows the move: a view asked for while it renders does not end
// it, and the next frame renders the newer view.
TEST(LiveRenderer, AViewsFirstFrameIsFinishedWhenTheNextViewArrives) {
  SceneDescription d = smallDefaultScene();
  d.render.width = 320;  // a frame of some milliseconds
  d.render.height = 180;
  const Scene scene(d);
  LiveOptions options = liveOptions(2, 1, 1);
  options.distribution.tileSize = 16;
  LiveRenderer renderer(scene, options);
  Recorder recorder;
  std::thread coordinator([&] { renderer.run(recorder); });
  renderer.setView({d.camera, 1, DebugView::Image});
  ASSERT_TRUE(recorder.waitForPasses(1));  // under way
  CameraDesc moved = d.camera;
  moved.position.x += 0.5f;
  renderer.setView({moved, 1, DebugView::Image});
  ASSERT_TRUE(recorder.waitForPass(2, 1));
  renderer.stop();
  coordinator.join();

  const std::vector<PassInfo> passes = recorder.passes();
  ASSERT_EQ(passes.size(), 2u);
  EXPECT_TRUE(recorder.finished(passes[0].frame));
  EXPECT_EQ(renderer.stats().ranks[0].staleTiles, 0u);
  EXPECT_TRUE(sameImage(recorder.image(passes[0].frame), renderedFrom(d, d.camera)));
  EXPECT_TRUE(sameImage(recorder.image(passes[1].frame), renderedFrom(d, moved)));
}

// While the camera moves, every frame that fits the target is full resolution, and each is
// exactly `prism render --spp 1` of its view; the next frame is queued before the last one's
// tiles are all back.
TEST(LiveRenderer, FramesWhileMovingAreFullResolutionAndBitIdenticalToRender) {
  const SceneDescription d = smallDefaultScene();
  const Scene scene(d);
  LiveOptions options = liveOptions(2, 4, 1);
  options.frameTimeSeconds = 10.0;  // every frame fits once one is measured
  options.distribution.tileSize = 8;
  LiveRenderer renderer(scene, options);
  Recorder recorder;
  std::thread coordinator([&] { renderer.run(recorder); });
  std::vector<CameraDesc> cameras;
  for (int i = 0; i < 8; ++i) {
    CameraDesc c = d.camera;
    c.position.x += 0.1f * static_cast<float>(i);
    cameras.push_back(c);
    renderer.setView({c, 1, DebugView::Image});
    std::this_thread::sleep_for(std::chrono::milliseconds(3));  // moves faster than frames
  }
  ASSERT_TRUE(recorder.waitForPasses(1));
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  // The last view's pass 1 ends the test.
  while (std::chrono::steady_clock::now() < deadline) {
    const std::vector<PassInfo> p = recorder.passes();
    if (!p.empty() && p.back().view->camera.position == cameras.back().position &&
        recorder.finished(p.back().frame)) {
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  renderer.stop();
  coordinator.join();

  const std::vector<PassInfo> passes = recorder.passes();
  ASSERT_GE(passes.size(), 2u);
  EXPECT_EQ(passes.front().scale.text(), "1/4");  // nothing measured yet: the cheapest frame
  int fullFrames = 0;                             // first frames of a view at full resolution
  for (const PassInfo& p : passes) {
    if (!recorder.finished(p.frame) || !p.scale.full()) continue;
    // A view's first frame, or its pass 1 after a reduced first frame when the next move came
    // later than that pass's end: both are `prism render` of the view.
    fullFrames += p.firstOfView;
    EXPECT_EQ(p.pass, 1);
    EXPECT_TRUE(sameImage(recorder.image(p.frame), renderedFrom(d, p.view->camera)))
        << "frame " << p.frame;
  }
  EXPECT_GE(fullFrames, 1);
  EXPECT_EQ(passes.back().view->camera.position, cameras.back().position);
  EXPECT_EQ(recorder.notCurrent(), 0u);
  const LiveStats stats = renderer.stats();
  EXPECT_GE(stats.frameTimes.frames, 2);
  EXPECT_GT(stats.frameTimes.medianSeconds, 0.0);
  EXPECT_GE(stats.frameTimes.p95Seconds, stats.frameTimes.medianSeconds);
  EXPECT_EQ(stats.frameTimes.shownWidth, d.render.width);
  EXPECT_EQ(stats.frameTimes.fullResolutionFrames, static_cast<uint64_t>(fullFrames));
}

// The viewer's photon-mapped passes, against maps and frames computed here from the building
// blocks: tests/data/scenes/caustic-small.yaml (40×30, 20000 photons, k = 40, α = 0.7).
SceneDescription causticScene() {
  return loadScene(PRISM_SOURCE_DIR "/tests/data/scenes/caustic-small.yaml");
}

const PhotonGather& gatherOf(const PassInfo& pass) {
  const auto* gather = dynamic_cast<const PhotonGather*>(pass.light->caustics.get());
  if (!gather) throw std::runtime_error("pass without a photon gather");
  return *gather;
}

// Pass `pass` of the scene's own camera as the viewer renders it: the pass's seed, and from pass
// 2 on one jittered sample per pixel when the pass has one (pass 1 is `prism render`).
ImageRgb renderPassFrame(SceneDescription d, int pass, std::shared_ptr<const RenderPass> light) {
  const Scene scene(d);
  RenderView view;
  view.camera = d.camera;
  view.width = d.render.width;
  view.height = d.render.height;
  view.samplesPerPixel = d.render.samplesPerPixel;
  view.seed = LiveRenderer::passSeed(d.render.seed, pass);
  view.jitterSingleSample = pass >= 2;
  const LightTerms terms = light ? light->terms() : LightTerms{};
  const TileResult whole =
      TileRenderer(scene, view, terms).render(0, {0, 0, view.width, view.height});
  ImageRgb image(view.width, view.height);
  image.pixels = whole.pixels;
  return image;
}

// Pass 1 of the scene's camera gathering from the photons traced for the pass of frame
// `photonFrame` (a later view's pass 1 reuses the first view's).
ImageRgb passOneWithPhotonsOf(const SceneDescription& d, uint32_t photonFrame) {
  const Scene scene(d);
  const PhotonTracer tracer(scene, d.caustics.photons, d.caustics.maxBounces);
  WorkDispatcher alone(scene, nullptr, {});
  PhotonPassStats stats;
  auto map =
      std::make_shared<const PhotonMap>(*tracePhotonPass(tracer, photonFrame, 2, alone, stats));
  const PhotonGatherSettings settings =
      progressiveGather(d.caustics, automaticMaxRadius(scene), 1, {});
  return renderPassFrame(
      d, 1, RenderPass::withPhotons(0, true, std::make_shared<const PhotonGather>(map, settings)));
}

double imageSum(const ImageRgb& image) {
  double sum = 0.0;
  for (const Color& c : image.pixels) sum += c.x + c.y + c.z;
  return sum;
}

TEST(LiveRenderer, PhotonMappedPassesAreProgressivePhotonMapping) {
  const SceneDescription d = causticScene();
  const Scene scene(d);
  const CausticSettings& c = d.caustics;
  constexpr int kPasses = 3;
  LiveOptions options = liveOptions(2, 2, kPasses);
  LiveRenderer renderer(scene, options);
  Recorder recorder;
  std::thread coordinator([&] { renderer.run(recorder); });
  renderer.setView({d.camera, 1, DebugView::Image, CausticMethod::PhotonMap, 0});
  ASSERT_TRUE(recorder.waitForFinished(1 + kPasses));
  renderer.stop();
  coordinator.join();

  const std::vector<PassInfo> passes = recorder.passes();
  ASSERT_EQ(passes.size(), 1u + kPasses);
  EXPECT_EQ(passes[0].pass, 0);
  EXPECT_EQ(passes[0].light, nullptr);  // the preview: direct light only

  // Pass i: the photon pass numbered by its frame id, the radius schedule of the scene.
  const PhotonTracer tracer(scene, c.photons, c.maxBounces);
  WorkDispatcher alone(scene, nullptr, {});
  PhotonGatherSettings settings;
  ImageRgb mean(d.render.width, d.render.height), expectedMean(d.render.width, d.render.height);
  ImageRgb causticMean(d.render.width, d.render.height);
  for (int i = 1; i <= kPasses; ++i) {
    const PassInfo& pass = passes[static_cast<size_t>(i)];
    ASSERT_EQ(pass.pass, i);
    ASSERT_NE(pass.light, nullptr);
    EXPECT_EQ(pass.light->index, pass.frame);
    EXPECT_TRUE(pass.light->direct);
    const PhotonGather& gather = gatherOf(pass);
    PhotonPassStats stats;
    const std::vector<Photon> photons = *tracePhotonPass(tracer, pass.frame, 2, alone, stats);
    ASSERT_EQ(gather.map().size(), photons.size());
    ASSERT_GT(photons.size(), 1000u);
    EXPECT_EQ(
        std::memcmp(gather.map().photons().data(), photons.data(), photons.size() * sizeof(Photon)),
        0);
    settings = progressiveGather(c, automaticMaxRadius(scene), i, settings);
    EXPECT_FALSE(gather.settings().fixedRadius);  // per-photon radii, the scene sets no radius
    EXPECT_EQ(gather.settings().k, c.gather);
    EXPECT_FLOAT_EQ(gather.settings().radius, settings.radius) << "pass " << i;
    EXPECT_FLOAT_EQ(gather.settings().radiusScale, settings.radiusScale) << "pass " << i;

    // Its image: direct light with pass i's seed plus pass i's estimate from map i.
    const ImageRgb expected = renderPassFrame(
        d, i,
        RenderPass::withPhotons(pass.frame, true,
                                std::make_shared<const PhotonGather>(
                                    std::make_shared<const PhotonMap>(photons), settings)));
    const ImageRgb got = recorder.image(pass.frame);
    ASSERT_EQ(got.pixels.size(), expected.pixels.size());
    for (size_t px = 0; px < got.pixels.size(); ++px) {
      ASSERT_EQ(got.pixels[px], expected.pixels[px]) << "pass " << i << " pixel " << px;
    }
    const ImageRgb direct = renderPassFrame(d, i, nullptr);
    for (size_t px = 0; px < got.pixels.size(); ++px) {
      mean.pixels[px] += got.pixels[px] / static_cast<float>(kPasses);
      causticMean.pixels[px] += (got.pixels[px] - direct.pixels[px]) / static_cast<float>(kPasses);
    }
  }
  EXPECT_LT(passes[1].frame, passes[2].frame);

  // The caustic part of the average against `prism render --progressive --passes 3`: other
  // photons (other pass numbers), the same estimator and radii, so the same light within noise.
  SceneDescription progressive = d;
  progressive.caustics.progressive = true;
  progressive.caustics.passes = kPasses;
  const Scene progressiveScene(progressive);
  FrameOptions frameOptions;
  frameOptions.distribution.threads = 2;
  const CausticFrame reference = renderWithCaustics(progressiveScene, frameOptions);
  EXPECT_EQ(reference.caustics.passes, kPasses);
  const ImageRgb referenceDirect = renderFrame(scene, frameOptions).image;
  double referenceCaustic = 0.0;
  for (size_t px = 0; px < referenceDirect.pixels.size(); ++px) {
    const Color c3 = reference.image.pixels[px] - referenceDirect.pixels[px];
    referenceCaustic += c3.x + c3.y + c3.z;
  }
  const double viewerCaustic = imageSum(causticMean);
  ASSERT_GT(referenceCaustic, 0.01 * imageSum(referenceDirect));  // there is a caustic
  // Within noise: other photons, and from pass 2 on other sample points (the viewer jitters its
  // 1-spp passes, `prism render` samples pixel centres), over a caustic of a few dozen 40×30
  // pixels, partly hidden behind the ball whose silhouette the pixels' footprints cross. Measured:
  // 1.116 with the estimate at the sample point, 1.17 with each pixel's footprint averaged.
  EXPECT_NEAR(viewerCaustic / referenceCaustic, 1.0, 0.2);

  const LiveStats stats = renderer.stats();
  EXPECT_EQ(stats.photons.method, CausticMethod::PhotonMap);
  EXPECT_EQ(stats.photons.passes, kPasses);
  EXPECT_EQ(stats.photons.photonsPerPass, c.photons);
  EXPECT_EQ(stats.photons.last.trace.stored, gatherOf(passes.back()).map().size());
  EXPECT_GT(stats.photons.last.mapBytes, stats.photons.last.trace.stored * sizeof(Photon) - 1);
  EXPECT_GT(stats.photons.last.photonsPerSecond(), 0.0);
  EXPECT_FLOAT_EQ(stats.photons.radius, settings.radius * settings.radiusScale);
}

// Photons do not depend on the view: a later view's pass 1 gathers from the first view's pass-1
// photons (the same estimator, its radii not found again), and a new budget traces pass 1 anew
// (passes 2 on trace their own: PhotonMappedPassesAreProgressivePhotonMapping). Pass 1 of the moved
// view is bit for bit its rendering with the map traced here for the first view's pass-1 frame.
TEST(LiveRenderer, ALaterViewsFirstPassReusesTheFirstViewsPhotons) {
  SceneDescription d = causticScene();
  const Scene scene(d);
  LiveOptions options = liveOptions(2, 1, 1);
  LiveRenderer renderer(scene, options);
  Recorder recorder;
  std::thread coordinator([&] { renderer.run(recorder); });
  renderer.setView({d.camera, 1, DebugView::Image, CausticMethod::PhotonMap, 0});
  ASSERT_TRUE(recorder.waitForFinished(2));  // pass 0 and 1 of the first view
  CameraDesc moved = d.camera;
  moved.position += Vec3(0.3f, 0.1f, 0.0f);
  renderer.setView({moved, 1, DebugView::Image, CausticMethod::PhotonMap, 0});
  ASSERT_TRUE(recorder.waitForFinished(4));
  const LiveStats movedStats = renderer.stats();
  renderer.setView({moved, 1, DebugView::Image, CausticMethod::PhotonMap, d.caustics.photons / 2});
  ASSERT_TRUE(recorder.waitForFinished(6));
  const LiveStats budgetStats = renderer.stats();
  renderer.stop();
  coordinator.join();

  const std::vector<PassInfo> passes = recorder.passes();
  ASSERT_EQ(passes.size(), 6u);
  const auto passOf = [&](size_t view, int pass) -> const PassInfo& {
    size_t seen = 0;
    uint64_t lastView = passes.front().viewId;
    for (const PassInfo& p : passes) {
      if (p.viewId != lastView) ++seen, lastView = p.viewId;
      if (seen == view && p.pass == pass) return p;
    }
    throw std::runtime_error("no such pass");
  };
  const PassInfo& first = passOf(0, 1);
  const PassInfo& later = passOf(1, 1);
  const PassInfo& otherBudget = passOf(2, 1);
  EXPECT_EQ(&gatherOf(later), &gatherOf(first));
  EXPECT_NE(&gatherOf(otherBudget), &gatherOf(first));
  EXPECT_LT(gatherOf(otherBudget).map().size(), gatherOf(first).map().size());
  EXPECT_EQ(later.light->index, later.frame);  // the tiles name the later pass's own frame
  EXPECT_TRUE(movedStats.photons.reused);
  EXPECT_EQ(movedStats.photons.passes, 1);
  EXPECT_FALSE(budgetStats.photons.reused);

  d.camera = moved;
  EXPECT_TRUE(sameImage(recorder.image(later.frame), passOneWithPhotonsOf(d, first.frame)));
}

// A move never waits for a photon pass: it cancels the one being traced.
TEST(LiveRenderer, AMoveCancelsThePhotonPassBeingTraced) {
  const SceneDescription d = causticScene();
  const Scene scene(d);
  LiveOptions options = liveOptions(2, 1, 2);
  LiveRenderer renderer(scene, options);
  Recorder recorder;
  std::thread coordinator([&] { renderer.run(recorder); });
  // 20 million photons: seconds of tracing for pass 1, which starts once pass 0 is done.
  constexpr uint64_t kPhotons = 20'000'000;
  renderer.setView({d.camera, 1, DebugView::Image, CausticMethod::PhotonMap, kPhotons});
  ASSERT_TRUE(recorder.waitForPass(1, 0));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));  // tracing now
  CameraDesc moved = d.camera;
  moved.position.x += 0.2f;
  const auto start = std::chrono::steady_clock::now();
  renderer.setView({moved, 1, DebugView::Image, CausticMethod::PhotonMap, kPhotons});
  ASSERT_TRUE(recorder.waitForPass(2, 0));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  renderer.stop();
  coordinator.join();

  // Cancelled within a chunk of photons: the new view came in a fraction of the whole pass's
  // tracing on the renderer's 2 threads, timed here.
  EXPECT_LT(seconds, test::projectedTraceSeconds(scene, kPhotons, 2) / 4);
  for (const PassInfo& p : recorder.passes()) EXPECT_NE(p.pass, 1) << "the cancelled pass ran";
  EXPECT_EQ(renderer.stats().photons.passes, 0);
}

TEST(LiveRenderer, SwitchingCausticsOrTheBudgetIsANewView) {
  const SceneDescription d = causticScene();
  const Scene scene(d);
  LiveOptions options = liveOptions(2, 1, 1);
  LiveRenderer renderer(scene, options);
  Recorder recorder;
  std::thread coordinator([&] { renderer.run(recorder); });
  renderer.setView({d.camera, 1, DebugView::Image, CausticMethod::None, 0});
  ASSERT_TRUE(recorder.waitForPass(1, 1));
  renderer.setView({d.camera, 1, DebugView::Image, CausticMethod::PhotonMap, 0});
  ASSERT_TRUE(recorder.waitForPass(2, 1));
  const LiveStats first = renderer.stats();
  renderer.setView({d.camera, 1, DebugView::Image, CausticMethod::PhotonMap, 5000});
  ASSERT_TRUE(recorder.waitForPass(3, 1));
  renderer.stop();
  coordinator.join();

  // Without photons a view's first frame is its pass 1; with them the first frame (pass 0) has
  // no photon caustics, which a move would wait for, and pass 1 traces them.
  std::vector<PassInfo> passes;
  for (const PassInfo& p : recorder.passes()) {
    if (p.pass == 1) passes.push_back(p);
  }
  ASSERT_EQ(passes.size(), 3u);
  EXPECT_EQ(recorder.passes().size(), 5u);
  EXPECT_EQ(recorder.passes()[1].pass, 0);
  EXPECT_EQ(recorder.passes()[1].light, nullptr);
  EXPECT_EQ(passes[0].light, nullptr);
  EXPECT_LT(passes[0].frame, passes[1].frame);
  EXPECT_LT(passes[1].frame, passes[2].frame);
  EXPECT_EQ(passes[1].viewId, passes[0].viewId + 1);
  EXPECT_EQ(passes[2].viewId, passes[1].viewId + 1);
  EXPECT_EQ(first.photons.photonsPerPass, 20000u);
  EXPECT_EQ(renderer.stats().photons.photonsPerPass, 5000u);
  // A quarter of the photons, a quarter of the map (give or take the roulette).
  const double ratio = static_cast<double>(gatherOf(passes[2]).map().size()) /
                       static_cast<double>(gatherOf(passes[1]).map().size());
  EXPECT_NEAR(ratio, 0.25, 0.02);
  // Pass 1 without caustics is `prism render --caustics none`.
  SceneDescription none = d;
  none.caustics.method = CausticMethod::None;
  const ImageRgb plain = renderFrame(Scene(none), FrameOptions{}).image;
  const ImageRgb got = recorder.image(passes[0].frame);
  for (size_t px = 0; px < got.pixels.size(); ++px) ASSERT_EQ(got.pixels[px], plain.pixels[px]);
  EXPECT_GT(imageSum(recorder.image(passes[1].frame)), imageSum(got));  // the caustic adds light
}

// The viewer over the loopback with a slave played by the test: the dispatcher `prism render`
// uses serves the viewer too, so a late PhotonShare (of a photon pass finished without it) is
// ignored instead of ending the viewer, and a tile the slave's heartbeat names lost comes back
// at once instead of after the lease.
TEST(LiveRenderer, OverTheLoopbackALatePhotonShareIsIgnoredAndALostTileComesBackAtOnce) {
  const SceneDescription d = smallDefaultScene();
  const Scene scene(d);
  LoopbackNetwork network(2);
  ScriptedSlave slave(network.endpoint(1), scene);
  // Ready and the late share are queued before the viewer starts, so the slave is known from the
  // first tile on and gets tiles however fast rank 0's own thread is.
  slave.ready();
  wire::PhotonShareMessage late{77, 0, 5, {}, 0.1, {}};
  late.photons.resize(5);
  slave.send(wire::encode(late));
  std::atomic<bool> stop{false};
  std::thread slaveThread([&] {
    bool lost = false;
    while (!stop) {
      const auto job = slave.nextJob(0.1);
      if (!job) continue;
      if (!lost) {
        slave.lose(job->tileIndex);
        slave.heartbeat();
        lost = true;
        continue;
      }
      slave.deliver(slave.render(*job));
    }
  });
  LiveOptions options = liveOptions(1, 1, 1);
  // Lease and silence never run out: only the heartbeat can bring the tile back (the recorder's
  // waits guard against the hang that would be otherwise).
  options.distribution.heartbeatTimeoutSeconds = test::kNeverSeconds;
  options.distribution.leaseSeconds = test::kNeverSeconds;
  LiveRenderer renderer(scene, options, &network.endpoint(0));
  Recorder recorder;
  std::exception_ptr failure;
  std::thread coordinator([&] {
    try {
      renderer.run(recorder);
    } catch (...) {
      failure = std::current_exception();
    }
  });
  renderer.setView({d.camera, d.render.samplesPerPixel, DebugView::Image});
  const bool finished = recorder.waitForFinished(1);
  const LiveStats stats = renderer.stats();
  renderer.stop();
  coordinator.join();
  stop = true;
  slaveThread.join();

  ASSERT_TRUE(finished);
  EXPECT_FALSE(failure);
  ASSERT_EQ(stats.ranks.size(), 2u);
  EXPECT_EQ(stats.ranks[1].lostTiles, 1u);
  EXPECT_GT(stats.ranks[1].tiles, 0u);
  EXPECT_FALSE(stats.ranks[1].retired);
  const std::vector<PassInfo> passes = recorder.passes();
  ASSERT_GE(passes.size(), 1u);
  EXPECT_EQ(passes[0].pass, 0);  // with slaves a view's first frame is only shown
  // This slave sends radiance whatever the frame (the master takes either form): exact.
  const ImageRgb expected = renderFrame(scene, FrameOptions{}).image;
  const ImageRgb first = recorder.image(passes[0].frame);
  ASSERT_EQ(first.pixels.size(), expected.pixels.size());
  EXPECT_EQ(std::memcmp(first.pixels.data(), expected.pixels.data(),
                        expected.pixels.size() * sizeof(Color)),
            0);
}

// A viewer slave that dies mid-pass costs the heartbeat timeout, not the lease.
TEST(LiveRenderer, OverTheLoopbackADeadSlaveIsRetiredWithinSeconds) {
  const SceneDescription d = smallDefaultScene();
  const Scene scene(d);
  LoopbackNetwork network(2);
  ScriptedSlave slave(network.endpoint(1), scene);
  slave.ready();  // known from the first tile on (see above)
  std::thread slaveThread([&] {
    slave.nextJob();  // takes its jobs and dies
    slave.nextJob();
  });
  LiveOptions options = liveOptions(1, 1, 1);
  options.distribution.heartbeatTimeoutSeconds = 0.6;
  options.distribution.leaseSeconds = 120.0;
  LiveRenderer renderer(scene, options, &network.endpoint(0));
  Recorder recorder;
  std::thread coordinator([&] { renderer.run(recorder); });
  renderer.setView({d.camera, d.render.samplesPerPixel, DebugView::Image});
  const bool finished = recorder.waitForFinished(1);
  const LiveStats stats = renderer.stats();
  renderer.stop();
  coordinator.join();
  slaveThread.join();
  ASSERT_TRUE(finished);  // within the recorder's 30 s; the lease is 120 s
  EXPECT_TRUE(stats.ranks[1].retired);
  // Rank 0 rendered every tile of the frame, the dead slave's too (and maybe some of pass 1,
  // which follows the shown-only first frame when there are slaves).
  EXPECT_GE(stats.ranks[0].tiles, recorder.passes()[0].tiles.size());
}

// Pipelined frames across real slaves (runSlave on a thread): a slave goes on to the next
// frame's tiles while the frame before it is still running (the View names the oldest frame
// still running, so its queued tiles stay), and every frame is bit-identical to one process's.
TEST(LiveRenderer, OverTheLoopbackPipelinedFramesWithARealSlaveAreBitIdentical) {
  const SceneDescription d = smallDefaultScene();
  const Scene scene(d);
  LoopbackNetwork network(2);
  int slaveExit = -1;
  std::thread slaveThread = test::startRealSlaveWithScene(network, d, &slaveExit);
  LiveOptions options = liveOptions(1, 1, 3);
  options.distribution.tileSize = 8;
  std::vector<CameraDesc> cameras;
  std::vector<PassInfo> passes;
  LiveStats stats;
  {
    LiveRenderer renderer(scene, options, &network.endpoint(0));
    Recorder recorder;
    std::thread coordinator([&] { renderer.run(recorder); });
    for (int i = 0; i < 5; ++i) {
      CameraDesc c = d.camera;
      c.position.y += 0.1f * static_cast<float>(i);
      cameras.push_back(c);
      renderer.setView({c, 1, DebugView::Image});
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    waitUntil([&] {  // the last view's three passes
      const std::vector<PassInfo> p = recorder.passes();
      return !p.empty() && p.back().pass == 3 && recorder.finished(p.back().frame);
    });
    stats = endLoopbackRun(renderer, coordinator, network);
    passes = recorder.passes();
    slaveThread.join();
    EXPECT_EQ(slaveExit, 0);

    ASSERT_GE(passes.size(), 3u);
    ASSERT_EQ(passes.back().pass, 3);
    EXPECT_EQ(passes.back().view->camera.position, cameras.back().position);
    int shownOnly = 0;
    for (const PassInfo& p : passes) {
      if (!recorder.finished(p.frame)) continue;
      SceneDescription from = d;
      from.camera = p.view->camera;
      const ImageRgb expected = p.pass <= 1 ? renderFrame(Scene(from), FrameOptions{}).image
                                            : renderPassFrame(from, p.pass, nullptr);
      if (p.pass == 0) {
        // A frame while moving is only shown: the slave's tiles came as display bytes, and the
        // frame shows exactly as `prism render`'s image does.
        ++shownOnly;
        EXPECT_EQ(p.view->displayExposure, d.render.exposure);
        const float exposure = d.render.exposure;
        EXPECT_EQ(toDisplayBytes(recorder.image(p.frame).pixels, exposure),
                  toDisplayBytes(expected.pixels, exposure));
      } else {
        EXPECT_EQ(p.view->displayExposure, 0.0f);
        EXPECT_TRUE(sameImage(recorder.image(p.frame), expected)) << "pass " << p.pass;
      }
    }
  }
  EXPECT_GT(stats.ranks[1].tiles, 0u);
  EXPECT_FALSE(stats.ranks[1].retired);
}

// With a real slave, a later view's pass 1 reuses the map the slave kept from the first view's
// pass 1 (PhotonMapAgain instead of the map): the frame is bit for bit its rendering with the
// photons traced for the first view's pass-1 frame, and the slave stays in.
TEST(LiveRenderer, OverTheLoopbackALaterViewsFirstPassGathersFromTheSlavesKeptMap) {
  SceneDescription d = causticScene();
  const Scene scene(d);
  LoopbackNetwork network(2);
  int slaveExit = -1;
  std::thread slaveThread = test::startRealSlaveWithScene(network, d, &slaveExit);
  LiveOptions options = liveOptions(1, 1, 1);
  options.distribution.tileSize = 8;
  CameraDesc moved = d.camera;
  moved.position += Vec3(0.3f, 0.1f, 0.0f);
  std::vector<PassInfo> passes;
  LiveStats stats;
  Recorder recorder;
  {
    LiveRenderer renderer(scene, options, &network.endpoint(0));
    std::thread coordinator([&] { renderer.run(recorder); });
    const auto passOneDone = [&](size_t views) {
      return waitUntil([&] {
        size_t done = 0;
        for (const PassInfo& p : recorder.passes())
          done += p.pass == 1 && recorder.finished(p.frame);
        return done == views;
      });
    };
    renderer.setView({d.camera, 1, DebugView::Image, CausticMethod::PhotonMap, 0});
    ASSERT_TRUE(passOneDone(1));
    renderer.setView({moved, 1, DebugView::Image, CausticMethod::PhotonMap, 0});
    ASSERT_TRUE(passOneDone(2));
    stats = endLoopbackRun(renderer, coordinator, network);
    passes = recorder.passes();
  }
  slaveThread.join();
  EXPECT_EQ(slaveExit, 0);
  EXPECT_GT(stats.ranks[1].tiles, 0u);
  EXPECT_FALSE(stats.ranks[1].retired);
  EXPECT_TRUE(stats.photons.reused);

  std::vector<const PassInfo*> ones;
  for (const PassInfo& p : passes) {
    if (p.pass == 1) ones.push_back(&p);
  }
  ASSERT_EQ(ones.size(), 2u);
  EXPECT_EQ(&gatherOf(*ones[1]), &gatherOf(*ones[0]));
  d.camera = moved;
  EXPECT_TRUE(sameImage(recorder.image(ones[1]->frame), passOneWithPhotonsOf(d, ones[0]->frame)));
}

// Frames while the camera moves (pass 0: reduced, shown and replaced) come from a slave as display
// bytes, 3 a pixel: the radiance that arrives is not the slave's, but the frame shows exactly as
// `prism render` of the same view does.
TEST(LiveRenderer, OverTheLoopbackFramesWhileMovingComeAsDisplayBytesAndShowAsRendered) {
  SceneDescription d = smallDefaultScene();
  d.render.exposure = 1.7f;
  const Scene scene(d);
  LoopbackNetwork network(2);
  int slaveExit = -1;
  std::thread slaveThread = test::startRealSlaveWithScene(network, d, &slaveExit);
  LiveOptions options;
  options.distribution.threads = 1;
  options.distribution.tileSize = 8;
  options.distribution.schedule = Schedule::Static;  // the slave renders its share of each frame
  options.previewScale = 2;
  options.frameTimeSeconds = 1e-6;  // no frame fits: every view starts at 1/2
  options.maxPasses = 1;
  std::vector<PassInfo> passes;
  Recorder recorder;
  LiveStats stats;
  {
    LiveRenderer renderer(scene, options, &network.endpoint(0));
    std::thread coordinator([&] { renderer.run(recorder); });
    const auto movingFramesShown = [&] {
      int n = 0;
      for (const PassInfo& p : recorder.passes()) n += p.pass == 0 && recorder.finished(p.frame);
      return n;
    };
    for (int i = 0; i < 3; ++i) {
      CameraDesc c = d.camera;
      c.position.x += 0.2f * static_cast<float>(i);
      renderer.setView({c, 1, DebugView::Image});
      waitUntil([&] { return movingFramesShown() > i; });
    }
    stats = endLoopbackRun(renderer, coordinator, network);
    passes = recorder.passes();
  }
  slaveThread.join();
  EXPECT_EQ(slaveExit, 0);
  EXPECT_GT(stats.ranks[1].tiles, 0u);
  int moving = 0;
  for (const PassInfo& p : passes) {
    if (p.pass != 0 || !recorder.finished(p.frame)) continue;
    ++moving;
    EXPECT_EQ(p.view->displayExposure, 1.7f);
    SceneDescription from = d;
    from.camera = p.view->camera;
    from.render.width = p.view->width;
    from.render.height = p.view->height;
    const ImageRgb expected = renderFrame(Scene(from), FrameOptions{}).image;
    const ImageRgb shown = recorder.image(p.frame);
    EXPECT_EQ(shown.width, d.render.width / 2);
    EXPECT_EQ(toDisplayBytes(shown.pixels, 1.7f), toDisplayBytes(expected.pixels, 1.7f));
    EXPECT_FALSE(sameImage(shown, expected));  // the slave's tiles came as bytes
  }
  EXPECT_EQ(moving, 3);
}

// Caustic maps the viewer may switch on (the scene itself uses photon maps) are checked against
// the memory limit: refused with the reason when they cannot fit, and held one set at a time
// (the blur on or off), which is what the check counts.
TEST(LiveRenderer, RefusesCausticMapsThatCannotFitAndHoldsOneSetAtATime) {
  SceneDescription d = test::ballOverFloorScene(1.5f);
  d.caustics.method = CausticMethod::PhotonMap;
  d.caustics.mapResolution = 64;
  const Scene scene(d);
  const uint64_t bytes = causticMapBytes(scene, 64);
  LiveOptions tight;
  tight.memoryLimit = {bytes - 1, "test"};
  LiveRenderer refusing(scene, tight);
  ASSERT_TRUE(refusing.causticMapsRefusal());
  EXPECT_NE(refusing.causticMapsRefusal()->find("caustic maps of 1 light at 64 texels a side"),
            std::string::npos);
  EXPECT_THROW(refusing.causticMaps(true), ResourceLimitError);

  LiveOptions roomy;
  roomy.memoryLimit = {bytes, "test"};
  LiveRenderer renderer(scene, roomy);
  EXPECT_FALSE(renderer.causticMapsRefusal());
  std::weak_ptr<const CausticMapEstimator> blurred = renderer.causticMaps(true);
  EXPECT_FALSE(blurred.expired());                        // kept for the next frame
  EXPECT_EQ(renderer.causticMaps(true), blurred.lock());  // and not built again
  const std::shared_ptr<const CausticMapEstimator> sharp = renderer.causticMaps(false);
  EXPECT_FALSE(sharp->empty());
  EXPECT_TRUE(blurred.expired());  // the other blur setting's maps went
}

// A slave checks such maps against its own limit (it may be a smaller machine than rank 0) and
// reports the refusal instead of building them; the viewer's run ends with its reason.
TEST(LiveRenderer, OverTheLoopbackASlaveRefusesCausticMapsBeyondItsOwnLimit) {
  SceneDescription d = test::ballOverFloorScene(1.5f);
  d.caustics.method = CausticMethod::PhotonMap;
  d.caustics.mapResolution = 64;
  d.render.width = 32;
  d.render.height = 24;
  const Scene scene(d);
  LoopbackNetwork network(2);
  int slaveExit = -1;
  std::thread slaveThread = test::startRealSlaveWithScene(
      network, d, &slaveExit, {causticMapBytes(scene, 64) - 1, "slave test"});
  LiveOptions options = liveOptions(1, 1, 1);
  options.distribution.tileSize = 8;
  options.distribution.schedule = Schedule::Static;  // the slave gets tiles of its own
  std::string failure;
  {
    LiveRenderer renderer(scene, options, &network.endpoint(0));
    ASSERT_FALSE(renderer.causticMapsRefusal());  // rank 0 has no limit
    Recorder recorder;
    std::atomic<bool> ended = false;
    std::thread coordinator([&] {
      try {
        renderer.run(recorder);
      } catch (const std::exception& e) {
        failure = e.what();
      }
      ended = true;
    });
    ViewSettings view{d.camera, 1, DebugView::Image};
    view.caustics = CausticMethod::CausticMap;
    renderer.setView(view);
    // run() ends on the slave's error; without one it would idle after the pass until stopped.
    waitUntil([&] { return ended.load(); }, 20.0);
    renderer.stop();
    coordinator.join();
    std::ostringstream err;
    shutDownSlaves(&network.endpoint(0), 1, {}, err);
  }
  slaveThread.join();
  EXPECT_EQ(slaveExit, 1);
  EXPECT_NE(failure.find("rank 1: caustic maps of 1 light at 64 texels a side (1 view) needs"),
            std::string::npos)
      << failure;
  EXPECT_NE(failure.find("slave test"), std::string::npos) << failure;
}

}  // namespace
}  // namespace prism
