#include "accel/Bvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "geometry/Sphere.h"
#include "math/Random.h"

namespace prism {
namespace {

std::vector<Sphere> randomSpheres(int count, uint64_t seed) {
  Pcg32 rng(seed, 1);
  std::vector<Sphere> spheres;
  for (int i = 0; i < count; ++i) {
    const Vec3 c(rng.nextFloat() * 20 - 10, rng.nextFloat() * 20 - 10, rng.nextFloat() * 20 - 10);
    spheres.push_back({c, 0.05f + 0.4f * rng.nextFloat(), 0});
  }
  return spheres;
}

TEST(Bvh, EveryPrimitiveAppearsOnceInLeafOrder) {
  const auto spheres = randomSpheres(1000, 3);
  std::vector<Aabb> bounds;
  for (const Sphere& s : spheres) bounds.push_back(s.bounds());
  Bvh bvh;
  bvh.build(bounds);
  std::vector<uint32_t> order = bvh.primitiveOrder();
  std::sort(order.begin(), order.end());
  for (uint32_t i = 0; i < order.size(); ++i) ASSERT_EQ(order[i], i);
  size_t inLeaves = 0;
  for (const BvhNode& n : bvh.nodes()) inLeaves += n.count;
  EXPECT_EQ(inLeaves, spheres.size());
  EXPECT_EQ(bvh.stats().nodeCount, bvh.nodes().size());
  EXPECT_GT(bvh.stats().memoryBytes, 0u);
}

TEST(Bvh, ChildBoxesLieInsideTheirParents) {
  const auto spheres = randomSpheres(500, 4);
  std::vector<Aabb> bounds;
  for (const Sphere& s : spheres) bounds.push_back(s.bounds());
  Bvh bvh;
  bvh.build(bounds);
  const auto& nodes = bvh.nodes();
  for (uint32_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i].isLeaf()) {
      for (uint32_t k = 0; k < nodes[i].count; ++k) {
        const Aabb& b = bounds[bvh.primitiveOrder()[nodes[i].offset + k]];
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(b.lower, nodes[i].bounds.lower)));
        EXPECT_TRUE(glm::all(glm::lessThanEqual(b.upper, nodes[i].bounds.upper)));
      }
      continue;
    }
    for (uint32_t child : {i + 1, nodes[i].offset}) {
      EXPECT_TRUE(
          glm::all(glm::greaterThanEqual(nodes[child].bounds.lower, nodes[i].bounds.lower)));
      EXPECT_TRUE(glm::all(glm::lessThanEqual(nodes[child].bounds.upper, nodes[i].bounds.upper)));
    }
  }
}

TEST(Bvh, ClosestHitMatchesBruteForce) {
  const auto spheres = randomSpheres(2000, 5);
  std::vector<Aabb> bounds;
  for (const Sphere& s : spheres) bounds.push_back(s.bounds());
  Bvh bvh;
  bvh.build(bounds);
  const auto& order = bvh.primitiveOrder();
  Pcg32 rng(6, 2);
  int hits = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 o(rng.nextFloat() * 30 - 15, rng.nextFloat() * 30 - 15, rng.nextFloat() * 30 - 15);
    const Vec3 d = glm::normalize(
        Vec3(rng.nextFloat() - 0.5f, rng.nextFloat() - 0.5f, rng.nextFloat() - 0.5f));
    const Ray ray{o, d};
    float bruteT = 1e30f;
    for (const Sphere& s : spheres) {
      float t;
      if (s.intersect(ray, bruteT, t)) bruteT = t;
    }
    float bvhT = 1e30f;
    bvh.traverse(ray, bvhT, false, [&](uint32_t first, uint32_t count, float& tMax) {
      bool found = false;
      for (uint32_t k = first; k < first + count; ++k) {
        float t;
        if (spheres[order[k]].intersect(ray, tMax, t)) {
          tMax = t;
          found = true;
        }
      }
      return found;
    });
    ASSERT_EQ(bvhT, bruteT) << "ray " << i;
    if (bruteT < 1e30f) ++hits;
  }
  EXPECT_GT(hits, 300);
}

TEST(Bvh, CoincidentPrimitivesStillSplitIntoSmallLeaves) {
  std::vector<Aabb> bounds(1000, Aabb{Vec3(0.0f), Vec3(1.0f)});
  Bvh bvh;
  bvh.build(bounds);
  for (const BvhNode& n : bvh.nodes()) EXPECT_LE(n.count, 8);
}

TEST(Bvh, EmptyBvhHitsNothing) {
  Bvh bvh;
  bvh.build({});
  float tMax = 1e30f;
  EXPECT_FALSE(bvh.traverse(Ray{}, tMax, false, [](uint32_t, uint32_t, float&) { return true; }));
}

TEST(Bvh, ParallelBuildGivesTheSerialTree) {
  const auto spheres = randomSpheres(100000, 8);  // above the size that gets a thread
  std::vector<Aabb> bounds;
  for (const Sphere& s : spheres) bounds.push_back(s.bounds());
  BvhBuildOptions serial, parallel;
  serial.threads = 1;
  parallel.threads = 4;
  Bvh a, b;
  a.build(bounds, serial);
  b.build(bounds, parallel);
  ASSERT_EQ(a.nodes().size(), b.nodes().size());
  EXPECT_EQ(a.primitiveOrder(), b.primitiveOrder());
  for (size_t i = 0; i < a.nodes().size(); ++i) {
    ASSERT_EQ(std::memcmp(&a.nodes()[i], &b.nodes()[i], sizeof(BvhNode)), 0) << i;
  }
  EXPECT_EQ(a.stats().leafCount, b.stats().leafCount);
  EXPECT_EQ(a.stats().maxDepth, b.stats().maxDepth);
}

bool sameTree(const Bvh& a, const Bvh& b) {
  if (a.nodes().size() != b.nodes().size() || a.primitiveOrder() != b.primitiveOrder()) {
    return false;
  }
  return std::memcmp(a.nodes().data(), b.nodes().data(), a.nodes().size() * sizeof(BvhNode)) == 0;
}

// Spheres and cones share leaves with packed triangles but are tested one by one: the SAH must
// charge each of them a full test, or it packs them four to a leaf as if they came at once.
TEST(Bvh, PrimitivesTestedAloneCostOneTestEachWhateverTheBlock) {
  const auto spheres = randomSpheres(20000, 9);
  std::vector<Aabb> bounds;
  for (const Sphere& s : spheres) bounds.push_back(s.bounds());
  BvhBuildOptions single, blocked, allAlone, half;
  blocked.primitiveBlock = allAlone.primitiveBlock = half.primitiveBlock = 4;
  allAlone.blockedFrom = static_cast<uint32_t>(bounds.size());
  half.blockedFrom = static_cast<uint32_t>(bounds.size() / 2);
  Bvh bySingle, byBlocked, byAllAlone, byHalf;
  bySingle.build(bounds, single);
  byBlocked.build(bounds, blocked);
  byAllAlone.build(bounds, allAlone);
  byHalf.build(bounds, half);
  EXPECT_TRUE(sameTree(bySingle, byAllAlone));
  EXPECT_FALSE(sameTree(bySingle, byBlocked));

  // With both kinds, leaves of lone-tested primitives stay smaller than leaves of blocked ones.
  size_t aloneLeaves = 0, aloneCount = 0, blockedLeaves = 0, blockedCount = 0;
  for (const BvhNode& n : byHalf.nodes()) {
    if (!n.isLeaf()) continue;
    uint32_t alone = 0;
    for (uint32_t i = n.offset; i < n.offset + n.count; ++i) {
      alone += byHalf.primitiveOrder()[i] < half.blockedFrom;
    }
    if (alone == n.count) {
      ++aloneLeaves;
      aloneCount += n.count;
    } else if (alone == 0) {
      ++blockedLeaves;
      blockedCount += n.count;
    }
  }
  ASSERT_GT(aloneLeaves, 100u);
  ASSERT_GT(blockedLeaves, 100u);
  const double aloneMean = static_cast<double>(aloneCount) / aloneLeaves;
  const double blockedMean = static_cast<double>(blockedCount) / blockedLeaves;
  EXPECT_LT(aloneMean, 0.75 * blockedMean) << aloneMean << " vs " << blockedMean;
}

}  // namespace
}  // namespace prism
