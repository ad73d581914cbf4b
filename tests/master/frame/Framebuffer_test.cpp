#include "master/frame/Framebuffer.h"

#include <gtest/gtest.h>

namespace prism {
namespace {

TileResult tile(uint32_t index, TileRect rect, float value) {
  TileResult t;
  t.tileIndex = index;
  t.rect = rect;
  t.pixels.assign(static_cast<size_t>(rect.pixelCount()), Color(value));
  return t;
}

TEST(Framebuffer, PlacesTilesAndIgnoresLateDuplicates) {
  Framebuffer fb(4, 2, 2);
  EXPECT_TRUE(fb.insert(tile(0, {0, 0, 2, 2}, 1.0f)));
  EXPECT_FALSE(fb.complete());
  EXPECT_FALSE(fb.insert(tile(0, {0, 0, 2, 2}, 9.0f)));  // duplicate
  EXPECT_TRUE(fb.insert(tile(1, {2, 0, 2, 2}, 2.0f)));
  EXPECT_TRUE(fb.complete());
  EXPECT_EQ(fb.image().at(1, 1).x, 1.0f);
  EXPECT_EQ(fb.image().at(3, 0).x, 2.0f);
}

TEST(Framebuffer, RejectsTilesThatDoNotFit) {
  Framebuffer fb(4, 4, 1);
  EXPECT_FALSE(fb.insert(tile(0, {3, 3, 2, 2}, 1.0f)));  // past the edge
  TileResult wrongSize = tile(0, {0, 0, 2, 2}, 1.0f);
  wrongSize.pixels.pop_back();
  EXPECT_FALSE(fb.insert(wrongSize));
  EXPECT_FALSE(fb.insert(tile(5, {0, 0, 2, 2}, 1.0f)));  // unknown tile index
  EXPECT_EQ(fb.tilesDone(), 0u);
}

}  // namespace
}  // namespace prism
