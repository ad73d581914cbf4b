#include "master/live/FrameAccumulator.h"

#include <gtest/gtest.h>

namespace prism {
namespace {

PassInfo pass(uint32_t frame, int index, int scale, int width, int height) {
  PassInfo p;
  p.frame = frame;
  p.viewId = 1;
  p.pass = index;
  p.scale = FrameScale{1, scale};
  auto view = std::make_shared<RenderView>();
  view->width = width;
  view->height = height;
  p.view = view;
  p.tiles = {{0, 0, width, height}};
  return p;
}

TileResult uniformTile(int width, int height, const Color& c) {
  TileResult t;
  t.tileIndex = 0;
  t.rect = {0, 0, width, height};
  t.pixels.assign(static_cast<size_t>(width) * height, c);
  return t;
}

TEST(FrameAccumulator, PreviewFillsBlocksAndFullPassesAverage) {
  FrameAccumulator f(8, 4);
  f.beginPass(pass(1, 0, 4, 2, 1));
  TileResult preview = uniformTile(2, 1, Color(1.0f));
  preview.pixels[1] = Color(0.5f);
  ASSERT_TRUE(f.addTile(1, preview));
  EXPECT_EQ(f.image().at(3, 3), Color(1.0f));  // left 4x4 block
  EXPECT_EQ(f.image().at(4, 0), Color(0.5f));  // right block
  EXPECT_TRUE(f.passComplete());

  f.beginPass(pass(2, 1, 1, 8, 4));  // pass 1 replaces the preview
  ASSERT_TRUE(f.addTile(2, uniformTile(8, 4, Color(0.2f))));
  EXPECT_EQ(f.image().at(7, 3), Color(0.2f));
  f.beginPass(pass(3, 2, 1, 8, 4));  // pass 2: mean of two
  ASSERT_TRUE(f.addTile(3, uniformTile(8, 4, Color(0.4f))));
  EXPECT_NEAR(f.image().at(0, 0).r, 0.3f, 1e-6f);
  f.beginPass(pass(4, 3, 1, 8, 4));  // pass 3: mean of three
  ASSERT_TRUE(f.addTile(4, uniformTile(8, 4, Color(0.9f))));
  EXPECT_NEAR(f.image().at(5, 2).g, 0.5f, 1e-6f);
}

// A view's first frame is shown whole: until its last tile is in, the screen keeps the frame
// before (never half of each view), then it replaces it at once.
TEST(FrameAccumulator, AViewsFirstFrameIsShownOnlyWhenComplete) {
  FrameAccumulator f(4, 2);
  f.beginPass(pass(1, 1, 1, 4, 2));
  ASSERT_TRUE(f.addTile(1, uniformTile(4, 2, Color(0.25f))));
  f.takeDirty();

  PassInfo moved = pass(2, 1, 1, 4, 2);
  moved.viewId = 2;
  moved.firstOfView = true;
  moved.tiles = {{0, 0, 2, 2}, {2, 0, 2, 2}};
  f.beginPass(moved);
  TileResult left = uniformTile(2, 2, Color(1.0f));
  ASSERT_TRUE(f.addTile(2, left));
  EXPECT_EQ(f.image().at(0, 0), Color(0.25f));  // still the frame before
  EXPECT_EQ(f.takeDirty().width, 0);            // nothing to repaint yet
  EXPECT_EQ(f.completedPass(), -1);
  TileResult right = uniformTile(2, 2, Color(0.5f));
  right.tileIndex = 1;
  right.rect = {2, 0, 2, 2};
  ASSERT_TRUE(f.addTile(2, right));
  EXPECT_EQ(f.image().at(0, 0), Color(1.0f));  // the whole new frame at once
  EXPECT_EQ(f.image().at(3, 1), Color(0.5f));
  const TileRect dirty = f.takeDirty();
  EXPECT_EQ(dirty.width, 4);
  EXPECT_EQ(dirty.height, 2);
  EXPECT_EQ(f.completedPass(), 1);

  // Pass 2 of the view refines in place, tile by tile.
  PassInfo second = pass(3, 2, 1, 4, 2);
  second.viewId = 2;
  f.beginPass(second);
  ASSERT_TRUE(f.addTile(3, uniformTile(4, 2, Color(0.0f))));
  EXPECT_EQ(f.image().at(0, 0), Color(0.5f));
}

TEST(FrameAccumulator, StaleTilesChangeNothing) {
  FrameAccumulator f(4, 4);
  f.beginPass(pass(7, 1, 1, 4, 4));
  EXPECT_FALSE(f.addTile(6, uniformTile(4, 4, Color(1.0f))));  // an ended frame
  EXPECT_FALSE(f.assign(6, 0, 1));
  EXPECT_EQ(f.image().at(0, 0), Color(0.0f));
  EXPECT_EQ(f.tilesDone(), 0u);
  EXPECT_EQ(f.staleTiles(), 1u);
  EXPECT_TRUE(f.addTile(7, uniformTile(4, 4, Color(1.0f))));
  EXPECT_FALSE(f.addTile(7, uniformTile(4, 4, Color(0.0f))));  // a duplicate
  EXPECT_EQ(f.image().at(0, 0), Color(1.0f));
}

TEST(FrameAccumulator, TracksTilesInFlightAndTheChangedRectangle) {
  FrameAccumulator f(8, 8);
  PassInfo p = pass(1, 0, 2, 4, 4);
  p.tiles = {{0, 0, 2, 4}, {2, 0, 2, 4}};
  f.beginPass(p);
  ASSERT_TRUE(f.assign(1, 1, 3));
  const auto inFlight = f.inFlight();
  ASSERT_EQ(inFlight.size(), 1u);
  EXPECT_EQ(inFlight[0].rank, 3);
  EXPECT_EQ(inFlight[0].rect.x, 4);  // preview pixels are 2x2 display pixels
  EXPECT_EQ(inFlight[0].rect.width, 4);
  EXPECT_EQ(inFlight[0].rect.height, 8);
  TileResult t = uniformTile(2, 4, Color(1.0f));
  t.tileIndex = 1;
  t.rect = {2, 0, 2, 4};
  ASSERT_TRUE(f.addTile(1, t));
  EXPECT_TRUE(f.inFlight().empty());
  const TileRect dirty = f.takeDirty();
  EXPECT_EQ(dirty.x, 4);
  EXPECT_EQ(dirty.width, 4);
  EXPECT_EQ(f.takeDirty().width, 0);
}

}  // namespace
}  // namespace prism
