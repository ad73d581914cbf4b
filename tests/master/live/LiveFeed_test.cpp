#include "master/live/LiveFeed.h"

#include <gtest/gtest.h>

#include "master/live/DisplayFrame.h"

namespace prism {
namespace {

PassInfo fullPass(uint32_t frame, int pass, int width, int height) {
  PassInfo p;
  p.frame = frame;
  p.viewId = 1;
  p.viewTag = 9;
  p.pass = pass;
  auto view = std::make_shared<RenderView>();
  view->width = width;
  view->height = height;
  view->samplesPerPixel = 2;
  p.view = view;
  p.firstOfView = pass == 1;
  p.tiles = {{0, 0, width, height / 2}, {0, height / 2, width, height - height / 2}};
  return p;
}

std::shared_ptr<const TileResult> tileOf(const PassInfo& p, uint32_t index, Color c) {
  auto tile = std::make_shared<TileResult>();
  tile->tileIndex = index;
  tile->rect = p.tiles[index];
  tile->pixels.assign(static_cast<size_t>(tile->rect.pixelCount()), c);
  return tile;
}

// The feed wakes its viewer once per take however much happens (once more when a pass begins or
// ends after other news: urgent), and a take holds everything since the last: the averaged
// passes as display bytes, the passes completed, the state.
TEST(LiveFeed, WakesOncePerTakeAndHandsOverTheAveragedPassesAsDisplayBytes) {
  LiveFeed feed(4, 2, 1.0f);
  int wakes = 0;
  int urgent = 0;
  feed.setWake([&](bool isUrgent) {
    ++wakes;
    urgent += isUrgent;
  });
  const PassInfo one = fullPass(1, 1, 4, 2);
  feed.passStarted(one);
  feed.tileAssigned(1, 0, 0);
  feed.tileAssigned(1, 1, 3);
  EXPECT_EQ(wakes, 1);  // the pass began: urgent
  EXPECT_EQ(urgent, 1);
  DisplayNews news = feed.take();
  ASSERT_EQ(news.inFlight.size(), 2u);
  EXPECT_EQ(news.inFlight[1].rank, 3);
  EXPECT_FALSE(news.hasPixels());  // a view's first pass shows once complete
  feed.tileFinished(1, tileOf(one, 0, Color(0.25f)), 0);
  feed.tileFinished(1, tileOf(one, 1, Color(0.25f)), 3);
  feed.passFinished(1, 0.1);
  const PassInfo two = fullPass(2, 2, 4, 2);
  feed.passStarted(two);
  feed.tileFinished(2, tileOf(two, 0, Color(0.75f)), 0);
  feed.tileFinished(2, tileOf(two, 1, Color(0.75f)), 0);
  feed.passFinished(2, 0.1);
  EXPECT_EQ(wakes, 3);  // a tile, then the pass's end (urgent), however many calls
  EXPECT_EQ(urgent, 2);
  news = feed.take();
  EXPECT_EQ(news.pass.pass, 2);
  EXPECT_EQ(news.pass.viewTag, 9u);
  EXPECT_EQ(news.pass.samplesPerPixel, 2);
  EXPECT_EQ(news.fullPassesDone, 2);
  ASSERT_EQ(news.completed.size(), 2u);
  EXPECT_EQ(news.completed[0].pass, 1);
  EXPECT_TRUE(news.hasPixels());
  DisplayFrame frame(4, 2);
  frame.apply(news);
  const DisplayEncoder encode(1.0f);
  for (const uint8_t b : frame.bytes()) EXPECT_EQ(b, encode(0.5f));  // (0.25 + 0.75) / 2
  EXPECT_EQ(feed.image().at(3, 1), Color(0.5f));
  EXPECT_TRUE(frame.passComplete());
  // Stale tiles change nothing and are counted.
  feed.tileFinished(1, tileOf(one, 0, Color(5.0f)), 0);
  EXPECT_EQ(feed.take().staleTiles, 1u);
  EXPECT_EQ(feed.image().at(0, 0), Color(0.5f));
}

}  // namespace
}  // namespace prism
