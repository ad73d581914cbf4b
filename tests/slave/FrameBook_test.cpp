#include "slave/FrameBook.h"

#include <gtest/gtest.h>

namespace prism {
namespace {

TEST(FrameBook, NothingRunningIsReportedAsFrameZero) {
  const FrameBook frames;
  const std::vector<wire::ProgressMessage> progress = frames.progress();
  ASSERT_EQ(progress.size(), 1u);
  EXPECT_EQ(progress[0].frame, 0u);
  EXPECT_EQ(progress[0].jobsReceived, 0u);
}

TEST(FrameBook, AJobOfALaterFrameEndsTheEarlierOnesAndAnEarlierJobIsStale) {
  FrameBook frames;
  FrameWork* first = frames.frameOfJob(3);
  ASSERT_NE(first, nullptr);
  const auto firstEnded = first->ended;
  ++first->received;
  first->held.insert(7);
  EXPECT_EQ(frames.frameOfJob(3), first);  // the same frame
  FrameWork* second = frames.frameOfJob(4);
  ASSERT_NE(second, nullptr);
  EXPECT_TRUE(*firstEnded);
  EXPECT_FALSE(*second->ended);
  EXPECT_EQ(frames.frameOfJob(3), nullptr);
  EXPECT_FALSE(frames.finish(3, 7));  // its result is stale
  const std::vector<wire::ProgressMessage> progress = frames.progress();
  ASSERT_EQ(progress.size(), 1u);
  EXPECT_EQ(progress[0].frame, 4u);
}

// The viewer pipelines its frames: a View ends the frames before liveFrom only.
TEST(FrameBook, AViewEndsTheFramesBeforeItsLiveFromOnly) {
  FrameBook frames;
  RenderView view;
  view.width = 17;
  const auto one = frames.startView(1, 1, view).ended;
  const auto two = frames.startView(2, 1, view).ended;
  FrameWork& three = frames.startView(3, 2, view);
  EXPECT_TRUE(*one);
  EXPECT_FALSE(*two);
  ASSERT_NE(three.view, nullptr);
  EXPECT_EQ(three.view->width, 17);
  EXPECT_EQ(frames.frameOfJob(2)->view->width, 17);  // a job of a running frame: its view
  const std::vector<wire::ProgressMessage> progress = frames.progress();
  ASSERT_EQ(progress.size(), 2u);
  EXPECT_EQ(progress[0].frame, 2u);
  EXPECT_EQ(progress[1].frame, 3u);
}

TEST(FrameBook, AFinishedTileIsNoLongerHeld) {
  FrameBook frames;
  FrameWork* frame = frames.frameOfJob(1);
  frame->received = 3;
  frame->held = {0, 1, 2};
  EXPECT_TRUE(frames.finish(1, 1));
  const wire::ProgressMessage p = frames.progress().at(0);
  EXPECT_EQ(p.jobsReceived, 3u);
  EXPECT_EQ(p.heldTiles, (std::vector<uint32_t>{0, 2}));
}

}  // namespace
}  // namespace prism
