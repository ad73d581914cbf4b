// The real-time projection of `prism speedup` against closed forms: uniform tiles on a free
// link, a link that is the bottleneck, and the scaling of measured costs to 1 spp.
#include "master/analysis/ScalingProjection.h"

#include <gtest/gtest.h>

#include <limits>

#include "master/frame/TilePlan.h"
#include "wire/Messages.h"

namespace prism {
namespace {

constexpr int kSize = 64;  // 16 tiles of 16 × 16
constexpr int kTile = 16;
constexpr double kTileSeconds = 0.01;

TileCostMap uniformCosts(double seconds) {
  const std::vector<TileRect> tiles = planTiles(kSize, kSize, kTile);
  return TileCostMap(kSize, kSize, tiles, std::vector<double>(tiles.size(), seconds));
}

SpeedupReport report(int samplesPerPixel, LinkModel link) {
  SpeedupReport r;
  r.width = r.height = kSize;
  r.samplesPerPixel = samplesPerPixel;
  r.threadsPerRank = 1;
  r.prefetch = 2;
  r.serialTileSize = kTile;
  r.link.model = link;
  return r;
}

ProjectionPlan plan(int maxWorkers) {
  ProjectionPlan p;
  p.sizes = {{kSize, kSize}};
  p.tileSize = kTile;
  p.maxWorkers = maxWorkers;
  return p;
}

TEST(ProjectFrameRates, UniformTilesOnAFreeLinkScaleWithTheWorkers) {
  const std::vector<FrameRatePoint> points =
      projectFrameRates(uniformCosts(kTileSeconds), plan(4), report(1, {}));
  ASSERT_EQ(points.size(), 3u);  // p = 1, 2, 4
  for (const FrameRatePoint& p : points) {
    // 16 tiles of 10 ms over p workers: a frame every 160 / p ms, pipelined or not.
    const double expected = p.workers / (16 * kTileSeconds);
    EXPECT_NEAR(p.framesPerSecond, expected, 1e-6 * expected) << p.workers << " workers";
    EXPECT_NEAR(p.unpipelinedFramesPerSecond, expected, 1e-6 * expected);
  }
}

TEST(ProjectFrameRates, PipeliningHidesTheRoundTripBetweenFrames) {
  LinkModel link;
  link.latencySeconds = 0.005;  // 5 ms each way: 10 ms of every unpipelined frame is waiting
  const std::vector<FrameRatePoint> points =
      projectFrameRates(uniformCosts(kTileSeconds), plan(4), report(1, link));
  for (const FrameRatePoint& p : points) {
    const double unpipelined = 1.0 / (16 * kTileSeconds / p.workers + 2 * link.latencySeconds);
    EXPECT_NEAR(p.unpipelinedFramesPerSecond, unpipelined, 0.02 * unpipelined);
    // Pipelined, only the first frame waits; 16 frames: within 1/16 of the compute bound.
    const double computeBound = p.workers / (16 * kTileSeconds);
    EXPECT_GT(p.framesPerSecond, p.unpipelinedFramesPerSecond);
    EXPECT_GT(p.framesPerSecond, 0.93 * computeBound);
    EXPECT_LE(p.framesPerSecond, computeBound * (1 + 1e-9));
  }
}

TEST(ProjectFrameRates, ALinkSlowerThanTheResultsBoundsTheRate) {
  LinkModel link;
  const double frameBytes = streamBytesPerSecond(kSize, kSize, kTile, 1.0);
  link.bytesPerSecond = 10.0 * frameBytes;  // 10 frames of results a second
  const std::vector<FrameRatePoint> points =
      projectFrameRates(uniformCosts(1e-6), plan(8), report(1, link));
  const FrameRatePoint& most = points.back();
  EXPECT_EQ(most.workers, 8);
  EXPECT_LE(most.framesPerSecond, 10.0 * (1 + 1e-9));
  EXPECT_GT(most.framesPerSecond, 9.0);
  EXPECT_NEAR(most.resultBytesPerSecond, most.framesPerSecond * frameBytes, 1e-6 * frameBytes);
}

TEST(ProjectFrameRates, MeasuredCostsAreScaledToOneSamplePerPixel) {
  // Measured at 4 spp: each tile cost 40 ms, so a 1-spp frame costs what 10 ms tiles do.
  const std::vector<FrameRatePoint> points =
      projectFrameRates(uniformCosts(4 * kTileSeconds), plan(1), report(4, {}));
  ASSERT_EQ(points.size(), 1u);
  EXPECT_NEAR(points[0].framesPerSecond, 1.0 / (16 * kTileSeconds), 1e-6);
}

TEST(StreamBytesPerSecond, IsTheResultMessagesOfEveryTileAsDisplayBytes) {
  // A moving camera's frames come as display bytes: 3 a pixel plus each tile's fixed part, 16
  // tiles here; radiance would be 12 a pixel.
  const double perFrame = streamBytesPerSecond(kSize, kSize, kTile, 1.0);
  EXPECT_NEAR(perFrame, 16 * tileResultBytes(kTile * kTile, true), 1e-9);
  EXPECT_GT(perFrame, 3.0 * kSize * kSize);
  EXPECT_LT(perFrame, 3.0 * kSize * kSize + 16 * 200);
  EXPECT_NEAR(tileResultBytes(kTile * kTile) - tileResultBytes(kTile * kTile, true),
              9.0 * kTile * kTile, 1e-9);
  // The sizes are those of real messages.
  wire::TileResultMessage m;
  m.result.rect = {0, 0, kTile, kTile};
  m.result.pixels.assign(static_cast<size_t>(kTile) * kTile, Color(0.25f));
  EXPECT_EQ(tileResultBytes(kTile * kTile), wire::encode(m).size());
  m.displayExposure = 1.0f;
  EXPECT_EQ(tileResultBytes(kTile * kTile, true), wire::encode(m).size());
  EXPECT_NEAR(streamBytesPerSecond(kSize, kSize, kTile, 30.0), 30 * perFrame, 1e-6);
}

}  // namespace
}  // namespace prism
