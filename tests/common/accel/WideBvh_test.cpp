#include "accel/WideBvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "math/Random.h"

namespace prism {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

Vec3 randomVec(Pcg32& rng, float lo, float hi) {
  return {lo + (hi - lo) * rng.nextFloat(), lo + (hi - lo) * rng.nextFloat(),
          lo + (hi - lo) * rng.nextFloat()};
}

std::vector<Aabb> randomBoxes(int count, uint64_t seed) {
  Pcg32 rng(seed, 7);
  std::vector<Aabb> boxes;
  for (int i = 0; i < count; ++i) {
    Aabb b;
    const Vec3 c = randomVec(rng, -10, 10);
    b.extend(c - randomVec(rng, 0, 1));
    b.extend(c + randomVec(rng, 0, 1));
    boxes.push_back(b);
  }
  return boxes;
}

// Leaves reached from the wide root, as (first entry, count) pairs.
void collectLeaves(const WideBvh& wide, uint32_t node, std::vector<std::pair<uint32_t, int>>& out) {
  const WideBvhNode& n = wide.nodes()[node];
  for (int i = 0; i < WideBvhNode::kWidth; ++i) {
    if (n.bounds[0][i] > n.bounds[1][i]) continue;  // unused slot
    if (n.count[i] > 0) {
      out.push_back({n.child[i], n.count[i]});
    } else {
      collectLeaves(wide, n.child[i], out);
    }
  }
}

TEST(WideBvh, KeepsEveryLeafOfTheBinaryBvh) {
  Bvh binary;
  binary.build(randomBoxes(3000, 1));
  WideBvh wide;
  wide.build(binary);
  std::vector<std::pair<uint32_t, int>> wideLeaves, binaryLeaves;
  collectLeaves(wide, 0, wideLeaves);
  for (const BvhNode& n : binary.nodes()) {
    if (n.isLeaf()) binaryLeaves.push_back({n.offset, n.count});
  }
  std::sort(wideLeaves.begin(), wideLeaves.end());
  std::sort(binaryLeaves.begin(), binaryLeaves.end());
  EXPECT_EQ(wideLeaves, binaryLeaves);
  EXPECT_LT(wide.nodes().size(), binary.nodes().size() / 4);
  EXPECT_EQ(wide.stats().memoryBytes, wide.nodes().size() * sizeof(WideBvhNode));
}

// Two far-apart rows of eight unit boxes: the SAH gives each box its own leaf, so each row is a
// subtree of eight leaves. Each row must become one full node; opening the rows into the root
// (as a plain largest-first collapse does) would leave eight nodes of two leaves below it.
TEST(WideBvh, ASubtreeOfAtMostEightLeavesBecomesOneNode) {
  std::vector<Aabb> boxes;
  for (int row = 0; row < 2; ++row) {
    for (int i = 0; i < 8; ++i) {
      const Vec3 lower(1000.0f * row + 2.0f * i, 0.0f, 0.0f);
      boxes.push_back({lower, lower + Vec3(1.0f)});
    }
  }
  Bvh binary;
  binary.build(boxes);
  size_t binaryLeaves = 0;
  for (const BvhNode& n : binary.nodes()) binaryLeaves += n.isLeaf();
  ASSERT_EQ(binaryLeaves, 16u);
  WideBvh wide;
  wide.build(binary);
  ASSERT_EQ(wide.nodes().size(), 3u);
  for (int node = 1; node < 3; ++node) {
    for (int i = 0; i < WideBvhNode::kWidth; ++i) EXPECT_EQ(wide.nodes()[node].count[i], 1);
  }
}

TEST(WideBvh, EmptyBvhIsNeverHit) {
  Bvh binary;
  binary.build({});
  WideBvh wide;
  wide.build(binary);
  EXPECT_TRUE(wide.nodes().empty());
  float tMax = kInf;
  const Ray ray{Vec3(0), Vec3(0, 0, 1)};
  EXPECT_FALSE(wide.traverse<false>(ray, tMax, [](uint32_t, uint32_t, float&) { return true; }));
}

TEST(WideBvh, SinglePrimitiveIsOneLeafUnderTheRoot) {
  Aabb box;
  box.extend(Vec3(-1));
  box.extend(Vec3(1));
  Bvh binary;
  binary.build({box});
  WideBvh wide;
  wide.build(binary);
  ASSERT_EQ(wide.nodes().size(), 1u);
  int visits = 0;
  const auto visitor = [&](uint32_t first, uint32_t count, float&) {
    EXPECT_EQ(first, 0u);
    EXPECT_EQ(count, 1u);
    ++visits;
    return true;
  };
  float tMax = kInf;
  EXPECT_TRUE(wide.traverse<false>({Vec3(0, 0, -5), Vec3(0, 0, 1)}, tMax, visitor));
  EXPECT_FALSE(wide.traverse<true>({Vec3(3, 0, -5), Vec3(0, 0, 1)}, tMax, visitor));
  EXPECT_EQ(visits, 1);
}

// The SIMD slab test and its scalar twin agree lane by lane, axis-parallel rays (infinite
// reciprocals, NaN where a ray lies in a slab plane) included.
TEST(WideBvh, SimdSlabTestMatchesTheScalarOne) {
  Pcg32 rng(11, 3);
  const std::vector<Aabb> boxes = randomBoxes(8, 5);
  Bvh binary;
  binary.build(boxes);
  WideBvh wide;
  wide.build(binary);
  WideBvhNode node = wide.nodes()[0];
  node.bounds[0][7] = kInf;  // an unused slot
  node.bounds[1][7] = -kInf;
  int entered = 0;
  for (int i = 0; i < 20000; ++i) {
    // Aimed near one of the boxes, so that a good share of the tests enter.
    const Aabb& target = boxes[i % boxes.size()];
    const Vec3 origin = randomVec(rng, -12, 12);
    Ray ray{origin, glm::normalize(target.center() + randomVec(rng, -1, 1) - origin)};
    if (i % 4 == 0) {
      ray.direction[i / 4 % 3] = (i % 8 == 0) ? 0.0f : -0.0f;
    }
    if (i % 16 == 0) ray.origin.x = node.bounds[0][i % 7];  // in a slab plane
    ray.tMin = 0.0f;
    const float tMax = (i % 3 == 0) ? 5.0f : kInf;
    float entryLanes[WideBvhNode::kWidth];
    const uint32_t mask =
        intersectChildren(node, WideRay(ray), simd::broadcast<SlabLanes>(tMax), entryLanes);
    float entry[WideBvhNode::kWidth];
    const uint32_t scalarMask = intersectChildrenScalar(node, ray, 0.0f, tMax, entry);
    ASSERT_EQ(mask, scalarMask) << i;
    for (int lane = 0; lane < WideBvhNode::kWidth; ++lane) {
      if (mask & (1u << lane)) {
        ASSERT_EQ(entryLanes[lane], entry[lane]) << i;
      }
    }
    EXPECT_EQ(mask & 0x80u, 0u);
    entered += __builtin_popcount(mask);
  }
  EXPECT_GT(entered, 1000);
}

// entersTree may only reject a ray that the root's node test rejects too: the shadow rays it
// turns away never reach the walk. Rays from outside the boxes, many missing them, some
// parallel to an axis (infinite reciprocals) and some starting in the plane of the box around
// them all (NaN slab distances), which is where the test's own box and the children's meet.
TEST(WideBvh, TreeBoxTestRejectsOnlyRaysTheRootRejects) {
  const std::vector<Aabb> boxes = randomBoxes(60, 9);
  Aabb all;
  for (const Aabb& b : boxes) all.extend(b);
  Bvh binary;
  binary.build(boxes);
  WideBvh wide;
  wide.build(binary);
  Pcg32 rng(5, 17);
  int rejected = 0, entered = 0;
  for (int i = 0; i < 50000; ++i) {
    const Vec3 origin = randomVec(rng, -30, 30);
    const Vec3 target = boxes[i % boxes.size()].center() + randomVec(rng, -15, 15);
    Ray ray{origin, glm::normalize(target - origin)};
    if (i % 5 == 0) ray.direction[i / 5 % 3] = (i % 10 == 0) ? 0.0f : -0.0f;
    if (i % 7 == 0) ray.origin[i % 3] = (i % 2) ? all.lower[i % 3] : all.upper[i % 3];
    const float tMax = (i % 3 == 0) ? 12.0f : kInf;
    if (wide.entersTree(ray, tMax)) {
      ++entered;
      continue;
    }
    ++rejected;
    float entry[WideBvhNode::kWidth];
    ASSERT_EQ(
        intersectChildren(wide.nodes()[0], WideRay(ray), simd::broadcast<SlabLanes>(tMax), entry),
        0u)
        << i;
  }
  EXPECT_GT(rejected, 5000);
  EXPECT_GT(entered, 5000);
  // An empty tree is entered by nothing.
  EXPECT_FALSE(WideBvh().entersTree(Ray{Vec3(0.0f), Vec3(0, 0, 1)}, kInf));
}

// The order a walk that never hits visits leaves in, worked out one node at a time with the
// scalar slab test: entered children nearest first, the later lane first on equal entry
// distances, each subtree finished before the next sibling.
void expectedVisits(const WideBvh& wide, uint32_t node, const Ray& ray,
                    std::vector<uint32_t>& visits, int& ties) {
  const WideBvhNode& n = wide.nodes()[node];
  float entry[WideBvhNode::kWidth];
  const uint32_t mask = intersectChildrenScalar(n, ray, ray.tMin, ray.tMax, entry);
  std::vector<int> lanes;
  for (int lane = 0; lane < WideBvhNode::kWidth; ++lane) {
    if (mask & (1u << lane)) lanes.push_back(lane);
  }
  std::sort(lanes.begin(), lanes.end(),
            [&](int a, int b) { return entry[a] != entry[b] ? entry[a] < entry[b] : a > b; });
  for (size_t i = 1; i < lanes.size(); ++i) ties += entry[lanes[i]] == entry[lanes[i - 1]];
  for (int lane : lanes) {
    if (n.count[lane] > 0) {
      visits.push_back(n.child[lane]);
    } else {
      expectedVisits(wide, n.child[lane], ray, visits, ties);
    }
  }
}

// Which of two equally near children a closest-hit walk visits first decides, when their leaves
// also hit at the same t, which primitive an image shows: the rule (the later lane first) is
// part of what keeps images the same from build to build. Nested boxes sharing a corner give
// equal entry distances to every ray that enters them through the shared faces.
TEST(WideBvh, ClosestHitWalkVisitsEqualEntriesLaterLaneFirst) {
  std::vector<Aabb> boxes;
  Pcg32 rng(41, 2);
  for (int i = 0; i < 400; ++i) {
    const Vec3 corner(static_cast<float>(i % 4) * 3.0f, 0.0f, static_cast<float>(i % 3) * 3.0f);
    boxes.push_back({corner, corner + Vec3(0.5f + 4.0f * rng.nextFloat())});
  }
  Bvh binary;
  binary.build(boxes);
  WideBvh wide;
  wide.build(binary);
  int ties = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 origin = Vec3(-4.0f, -4.0f, -4.0f) + randomVec(rng, -2, 2);
    const Vec3 target = randomVec(rng, 0.0f, 9.0f);
    const Ray ray{origin, glm::normalize(target - origin)};
    std::vector<uint32_t> visits, expected;
    float tMax = ray.tMax;
    wide.traverse<false>(ray, tMax, [&](uint32_t first, uint32_t, float&) {
      visits.push_back(first);
      return false;
    });
    expectedVisits(wide, 0, ray, expected, ties);
    ASSERT_EQ(visits, expected) << "ray " << i;
  }
  EXPECT_GT(ties, 1000);
}

TEST(WideBvh, ReportsTheInstructionSetItWasBuiltFor) {
  EXPECT_NE(std::string(simd::compiledInstructionSet()), "");
}

}  // namespace
}  // namespace prism
