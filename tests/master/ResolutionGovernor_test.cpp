#include "master/ResolutionGovernor.h"

#include <gtest/gtest.h>

namespace prism {
namespace {

constexpr int kWidth = 640;
constexpr int kHeight = 360;
constexpr double kPixels = 640.0 * 360.0;

TEST(ResolutionGovernor, StartsAtTheLargestDropUntilAFrameIsMeasured) {
  const ResolutionGovernor governor(1.0 / 30, 4);
  EXPECT_EQ(governor.scaleFor(kWidth, kHeight), 4);
  EXPECT_EQ(governor.samplesPerSecond(), 0.0);
}

TEST(ResolutionGovernor, FullResolutionWhenAFrameFitsTheTarget) {
  ResolutionGovernor governor(1.0 / 30, 4);
  governor.frameFinished(static_cast<uint64_t>(kPixels), 0.020);  // 20 ms at full resolution
  EXPECT_EQ(governor.scaleFor(kWidth, kHeight), 1);
}

TEST(ResolutionGovernor, DropsOnlyAsFarAsNeededAndComesBackWhenItFits) {
  ResolutionGovernor governor(1.0 / 30, 4);
  // 60 ms per full frame: 1/2 of each side (15 ms) fits, full (60 ms) does not.
  for (int i = 0; i < 5; ++i) governor.frameFinished(static_cast<uint64_t>(kPixels), 0.060);
  EXPECT_EQ(governor.scaleFor(kWidth, kHeight), 2);
  // 200 ms per full frame: 1/3 is 22 ms.
  for (int i = 0; i < 5; ++i) governor.frameFinished(static_cast<uint64_t>(kPixels), 0.200);
  EXPECT_EQ(governor.scaleFor(kWidth, kHeight), 3);
  // The machine is free again: reduced frames measure the rate, and it comes back up.
  for (int i = 0; i < 5; ++i) governor.frameFinished(static_cast<uint64_t>(kPixels / 4), 0.006);
  EXPECT_EQ(governor.scaleFor(kWidth, kHeight), 1);
}

TEST(ResolutionGovernor, NeverDropsBelowTheLargestScale) {
  ResolutionGovernor governor(1.0 / 30, 4);
  governor.frameFinished(static_cast<uint64_t>(kPixels), 10.0);  // hopeless
  EXPECT_EQ(governor.scaleFor(kWidth, kHeight), 4);
}

TEST(ResolutionGovernor, OneSlowFrameAmongFastOnesDoesNotDropTheResolution) {
  ResolutionGovernor governor(1.0 / 30, 4);
  for (int i = 0; i < 4; ++i) governor.frameFinished(static_cast<uint64_t>(kPixels), 0.020);
  governor.frameFinished(static_cast<uint64_t>(kPixels), 0.500);  // the machine hiccupped
  EXPECT_EQ(governor.scaleFor(kWidth, kHeight), 1);
}

TEST(ResolutionGovernor, WithoutATargetAlwaysFullResolution) {
  ResolutionGovernor governor(0.0, 4);
  EXPECT_EQ(governor.scaleFor(kWidth, kHeight), 1);
  governor.frameFinished(static_cast<uint64_t>(kPixels), 10.0);
  EXPECT_EQ(governor.scaleFor(kWidth, kHeight), 1);
}

TEST(ResolutionGovernor, IgnoresFramesWithoutTimeOrSamples) {
  ResolutionGovernor governor(1.0 / 30, 4);
  governor.frameFinished(0, 0.01);
  governor.frameFinished(1000, 0.0);
  EXPECT_EQ(governor.samplesPerSecond(), 0.0);
  EXPECT_EQ(governor.scaleFor(kWidth, kHeight), 4);
}

}  // namespace
}  // namespace prism
