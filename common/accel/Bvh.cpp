#include "accel/Bvh.h"

#include <algorithm>
#include <array>

#include "util/Stopwatch.h"

namespace prism {
namespace {

constexpr int kBinCount = 16;
constexpr uint32_t kMaxLeafSize = 8;
// SAH costs relative to one primitive test; a node visit costs about one box test.
constexpr float kTraversalCost = 1.0f;
constexpr float kIntersectionCost = 1.0f;
// Subtrees below this size are not worth a thread.
constexpr uint32_t kParallelMinPrimitives = 32768;

struct Builder {
  const std::vector<Aabb>& bounds;
  const std::vector<Vec3>& centers;
  std::vector<uint32_t>& order;
  std::vector<BvhNode>& nodes;
  BvhBuildStats& stats;
  uint32_t block = 1;
  int parallelLevels = 0;  // this many levels below the root build their right half on a thread

  float blocks(uint32_t count) const { return static_cast<float>((count + block - 1) / block); }

  uint32_t build(uint32_t begin, uint32_t end, size_t depth) {
    const uint32_t nodeIndex = static_cast<uint32_t>(nodes.size());
    nodes.emplace_back();
    stats.maxDepth = std::max(stats.maxDepth, depth);
    Aabb box, centerBox;
    for (uint32_t i = begin; i < end; ++i) {
      box.extend(bounds[order[i]]);
      centerBox.extend(centers[order[i]]);
    }
    nodes[nodeIndex].bounds = box;
    const uint32_t count = end - begin;

    int axis = -1;
    uint32_t middle = begin;
    if (count > 1 && (depth < Bvh::kMaxDepth || count > kMaxLeafSize))
      chooseSplit(begin, end, box, centerBox, axis, middle);
    if (axis < 0) {
      makeLeaf(nodeIndex, begin, count);
      return nodeIndex;
    }
    uint32_t second;
    if (static_cast<int>(depth) < parallelLevels && count >= kParallelMinPrimitives) {
      second = buildHalvesInParallel(begin, middle, end, depth);
    } else {
      build(begin, middle, depth + 1);
      second = build(middle, end, depth + 1);
    }
    nodes[nodeIndex].offset = second;
    nodes[nodeIndex].splitAxis = static_cast<uint8_t>(axis);
    return nodeIndex;
  }

  // The right half is built into its own array on another thread (the halves partition
  // disjoint ranges of order), then appended: the nodes come out exactly as a serial build
  // lays them out, so the tree does not depend on the number of threads.
  uint32_t buildHalvesInParallel(uint32_t begin, uint32_t middle, uint32_t end, size_t depth) {
    std::vector<BvhNode> rightNodes;
    rightNodes.reserve(2 * (end - middle));
    BvhBuildStats rightStats;
    Builder right{bounds, centers, order, rightNodes, rightStats, block, parallelLevels};
    parallelFor(2, 2, [&](uint64_t half) {
      if (half == 0) {
        build(begin, middle, depth + 1);
      } else {
        right.build(middle, end, depth + 1);
      }
    });
    const uint32_t base = static_cast<uint32_t>(nodes.size());
    for (BvhNode node : rightNodes) {
      if (!node.isLeaf()) node.offset += base;
      nodes.push_back(node);
    }
    stats.leafCount += rightStats.leafCount;
    stats.maxDepth = std::max(stats.maxDepth, rightStats.maxDepth);
    return base;
  }

  void makeLeaf(uint32_t nodeIndex, uint32_t begin, uint32_t count) {
    nodes[nodeIndex].offset = begin;
    nodes[nodeIndex].count = static_cast<uint16_t>(count);
    ++stats.leafCount;
  }

  // Picks the binned-SAH split, or axis = -1 when a leaf is cheaper (and allowed).
  void chooseSplit(uint32_t begin, uint32_t end, const Aabb& box, const Aabb& centerBox, int& axis,
                   uint32_t& middle) {
    const uint32_t count = end - begin;
    const float leafCost = kIntersectionCost * blocks(count);
    float bestCost = std::numeric_limits<float>::infinity();
    int bestAxis = -1;
    int bestBin = 0;
    const Vec3 extent = centerBox.extent();
    for (int a = 0; a < 3; ++a) {
      if (!(extent[a] > 0.0f)) continue;
      std::array<Aabb, kBinCount> binBoxes;
      std::array<uint32_t, kBinCount> binCounts{};
      const float scale = kBinCount / extent[a];
      for (uint32_t i = begin; i < end; ++i) {
        const int bin = binOf(centers[order[i]][a], centerBox.lower[a], scale);
        binBoxes[bin].extend(bounds[order[i]]);
        ++binCounts[bin];
      }
      // Sweep from the right to get the area and count of every right-hand side.
      std::array<float, kBinCount> rightArea{};
      std::array<uint32_t, kBinCount> rightCount{};
      Aabb accumulated;
      uint32_t accumulatedCount = 0;
      for (int b = kBinCount - 1; b > 0; --b) {
        accumulated.extend(binBoxes[b]);
        accumulatedCount += binCounts[b];
        rightArea[b] = accumulated.surfaceArea();
        rightCount[b] = accumulatedCount;
      }
      Aabb left;
      uint32_t leftCount = 0;
      for (int b = 1; b < kBinCount; ++b) {
        left.extend(binBoxes[b - 1]);
        leftCount += binCounts[b - 1];
        if (leftCount == 0 || rightCount[b] == 0) continue;
        const float cost =
            left.surfaceArea() * blocks(leftCount) + rightArea[b] * blocks(rightCount[b]);
        if (cost < bestCost) {
          bestCost = cost;
          bestAxis = a;
          bestBin = b;
        }
      }
    }
    if (bestAxis < 0) {
      // Every centre coincides: no SAH split exists. Small sets become a leaf, large ones are
      // halved by index so a leaf never exceeds kMaxLeafSize.
      if (count > kMaxLeafSize) {
        axis = box.longestAxis();
        middle = begin + count / 2;
      }
      return;
    }
    const float parentArea = std::max(box.surfaceArea(), 1e-30f);
    const float splitCost = kTraversalCost + kIntersectionCost * bestCost / parentArea;
    if (count <= kMaxLeafSize && splitCost >= leafCost) return;
    const float scale = kBinCount / extent[bestAxis];
    const float lower = centerBox.lower[bestAxis];
    auto* split = std::partition(order.data() + begin, order.data() + end, [&](uint32_t p) {
      return binOf(centers[p][bestAxis], lower, scale) < bestBin;
    });
    axis = bestAxis;
    middle = static_cast<uint32_t>(split - order.data());
  }

  static int binOf(float value, float lower, float scale) {
    const int bin = static_cast<int>((value - lower) * scale);
    return std::clamp(bin, 0, kBinCount - 1);
  }
};

}  // namespace

void Bvh::build(const std::vector<Aabb>& primitiveBounds, const BvhBuildOptions& options) {
  const auto start = SteadyClock::now();
  nodes_.clear();
  order_.resize(primitiveBounds.size());
  stats_ = {};
  for (uint32_t i = 0; i < order_.size(); ++i) order_[i] = i;
  if (!primitiveBounds.empty()) {
    std::vector<Vec3> centers;
    centers.reserve(primitiveBounds.size());
    for (const Aabb& b : primitiveBounds) centers.push_back(b.center());
    // One level of threads per doubling of the cores: two cores build two halves at once.
    int levels = 0;
    for (unsigned cores = std::max(1u, options.threads); cores > 1; cores /= 2) ++levels;
    Builder builder{primitiveBounds, centers, order_,
                    nodes_,          stats_,  std::max(1u, options.primitiveBlock),
                    levels};
    nodes_.reserve(2 * primitiveBounds.size());
    builder.build(0, static_cast<uint32_t>(primitiveBounds.size()), 0);
    nodes_.shrink_to_fit();
  }
  stats_.nodeCount = nodes_.size();
  stats_.memoryBytes = nodes_.size() * sizeof(BvhNode) + order_.size() * sizeof(uint32_t);
  stats_.seconds = secondsSince(start);
}

}  // namespace prism
