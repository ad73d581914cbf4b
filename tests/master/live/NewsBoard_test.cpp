#include "master/live/NewsBoard.h"

#include <gtest/gtest.h>

#include "master/live/DisplayFrame.h"

namespace prism {
namespace {

DisplayNews patchNews(int width, int height, TileRect rect, uint8_t value, int pass) {
  DisplayNews news;
  news.started = true;
  news.width = width;
  news.height = height;
  news.pass.pass = pass;
  news.pass.frame = static_cast<uint32_t>(pass);
  news.completed = {news.pass};
  news.patch = rect;
  news.patchBytes.assign(static_cast<size_t>(rect.width) * rect.height * 3, value);
  return news;
}

TEST(NewsBoard, NewsNotTakenIsMergedIntoTheUnionOfItsPatches) {
  NewsBoard board(8, 4);
  EXPECT_FALSE(board.hasNews());
  board.post(patchNews(8, 4, {0, 0, 2, 1}, 10, 1));
  board.post(patchNews(8, 4, {5, 2, 3, 2}, 20, 2));
  board.post(patchNews(8, 4, {1, 0, 1, 1}, 30, 3));  // over the first
  EXPECT_TRUE(board.hasNews());
  const DisplayNews news = board.take();
  EXPECT_FALSE(board.hasNews());
  EXPECT_EQ(news.patch.x, 0);
  EXPECT_EQ(news.patch.y, 0);
  EXPECT_EQ(news.patch.width, 8);
  EXPECT_EQ(news.patch.height, 4);
  ASSERT_EQ(news.completed.size(), 3u);  // every pass completed meanwhile, in order
  EXPECT_EQ(news.completed[2].pass, 3);
  EXPECT_EQ(news.pass.pass, 3);  // the newest state
  DisplayFrame frame(8, 4);
  frame.apply(news);
  EXPECT_EQ(frame.bytes()[0], 10);
  EXPECT_EQ(frame.bytes()[3], 30);
  EXPECT_EQ(frame.bytes()[(2 * 8 + 5) * 3], 20);
  EXPECT_EQ(frame.bytes()[(1 * 8 + 4) * 3], 0);  // inside the union, never painted
  // Taken: nothing changed since.
  EXPECT_FALSE(board.take().hasPixels());
  // Whole: every pixel, as for a viewer that just came.
  EXPECT_EQ(board.take(true).patchBytes.size(), 8u * 4 * 3);
}

TEST(NewsBoard, OnlyTheNewestCompletedPassesAreKept) {
  NewsBoard board(2, 2);
  for (int pass = 1; pass <= 100; ++pass) board.passCompleted(DisplayPass{.pass = pass});
  const DisplayNews news = board.take();
  ASSERT_EQ(news.completed.size(), DisplayNews::kMaxCompleted);
  EXPECT_EQ(news.completed.front().pass, 100 - static_cast<int>(DisplayNews::kMaxCompleted) + 1);
  EXPECT_EQ(news.completed.back().pass, 100);
}

TEST(NewsBoard, PatchesOutsideTheFrameOrOfAnotherFrameAreRefused) {
  NewsBoard board(8, 4);
  EXPECT_THROW(board.post(patchNews(8, 4, {6, 0, 3, 1}, 1, 1)), std::invalid_argument);
  EXPECT_THROW(board.post(patchNews(9, 4, {0, 0, 1, 1}, 1, 1)), std::invalid_argument);
  DisplayNews short_ = patchNews(8, 4, {0, 0, 2, 2}, 1, 1);
  short_.patchBytes.pop_back();
  EXPECT_THROW(board.post(std::move(short_)), std::invalid_argument);
  EXPECT_FALSE(board.hasNews());
}

}  // namespace
}  // namespace prism
