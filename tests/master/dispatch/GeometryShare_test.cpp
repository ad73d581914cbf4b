// The rule that chooses between every rank building its geometry and rank 0 broadcasting its
// own (docs/distributed.md, "One build per job"), against predictions worked out by hand.
#include "master/dispatch/GeometryShare.h"

#include <gtest/gtest.h>

#include <vector>

namespace prism {
namespace {

// Three ranks sharing one 2-core machine, 2 build threads each: a rank's build gets 2/3 of a core.
const BuildPlace kSharedRank{2, 2, 3};

// 5 M triangles over a link of 1 GB/s (86 MB in 0.086 s): every rank building takes
// 5e6 · 0.5 µs / (2/3) = 3.75 s; broadcasting, rank 0's build alone at 2 threads (1.25 s) plus
// 5e6 · 68 bytes over the link (0.34 s) and the codec (0.68 s): 2.27 s, of which 1.02 s transfer.
TEST(GeometryShare, SharedCoresAndAFastLinkBroadcastABigGeometry) {
  const GeometrySharePlan plan = planGeometryShare(GeometryShareMode::Auto, 5000000, 86000000,
                                                   0.086, kSharedRank, {kSharedRank, kSharedRank});
  EXPECT_NEAR(plan.linkBytesPerSecond, 1e9, 1.0);
  EXPECT_NEAR(plan.eachBuildsSeconds, 3.75, 1e-9);
  EXPECT_NEAR(plan.transferSeconds, 1.02, 1e-9);
  EXPECT_NEAR(plan.broadcastSeconds, 2.27, 1e-9);
  EXPECT_TRUE(plan.broadcast);
  // Long enough to send while rank 0 renders (DispatchSession::GeometrySending).
  EXPECT_GE(plan.transferSeconds, kSendWhileRenderingSeconds);
}

// The same over 10 MB/s: the transfer alone (34 s) outlasts every rank building.
TEST(GeometryShare, ASlowLinkBuildsOnEveryRank) {
  const GeometrySharePlan plan = planGeometryShare(GeometryShareMode::Auto, 5000000, 86000000, 8.6,
                                                   kSharedRank, {kSharedRank, kSharedRank});
  EXPECT_NEAR(plan.transferSeconds, 34.0 + 0.68, 1e-9);
  EXPECT_FALSE(plan.broadcast);
}

// A small scene's geometry (1000 triangles, 68 kB) travels in well under the 0.1 s that makes
// rendering during the broadcast worth it: it goes before the frame.
TEST(GeometryShare, ASmallGeometryIsNotWorthSendingWhileRendering) {
  const GeometrySharePlan plan = planGeometryShare(GeometryShareMode::Broadcast, 1000, 20000, 0.001,
                                                   kSharedRank, {kSharedRank});
  EXPECT_TRUE(plan.broadcast);
  EXPECT_LT(plan.transferSeconds, kSendWhileRenderingSeconds);
}

// Forced choices win over the prediction; with no slave there is nothing to broadcast.
TEST(GeometryShare, ForcedChoicesAndNoSlaves) {
  EXPECT_FALSE(planGeometryShare(GeometryShareMode::Local, 5000000, 86000000, 0.086, kSharedRank,
                                 {kSharedRank})
                   .broadcast);
  EXPECT_TRUE(planGeometryShare(GeometryShareMode::Broadcast, 5000000, 86000000, 8.6, kSharedRank,
                                {kSharedRank})
                  .broadcast);
  EXPECT_FALSE(
      planGeometryShare(GeometryShareMode::Broadcast, 5000000, 86000000, 0.086, kSharedRank, {})
          .broadcast);
}

}  // namespace
}  // namespace prism
