#include "accel/Bvh.h"

#include <algorithm>
#include <array>
#include <memory>

#include "math/Simd.h"
#include "util/HugePages.h"
#include "util/Stopwatch.h"

namespace prism {
namespace {

using simd::Float4;
using simd::Int4;

constexpr int kBinCount = 16;
constexpr uint32_t kMaxLeafSize = 8;
// SAH costs relative to one primitive test; a node visit costs about one box test.
constexpr float kTraversalCost = 1.0f;
constexpr float kIntersectionCost = 1.0f;
// Subtrees below this size are not worth a thread (starting one costs tens of microseconds; a
// 4096-primitive half takes about a millisecond).
constexpr uint32_t kParallelMinPrimitives = 4096;
constexpr float kInf = std::numeric_limits<float>::infinity();

// A box as two SIMD registers (x, y, z, unused). extend() keeps Aabb::extend's operand order,
// (new < old ? new : old), so every bound is bit for bit what the scalar code computes.
struct Box4 {
  Float4 lower = {kInf, kInf, kInf, kInf};
  Float4 upper = {-kInf, -kInf, -kInf, -kInf};

  void extend(const Box4& b) {
    lower = simd::minLanes(b.lower, lower);
    upper = simd::maxLanes(b.upper, upper);
  }
  void extendPoint(Float4 p) {
    lower = simd::minLanes(p, lower);
    upper = simd::maxLanes(p, upper);
  }
  Aabb aabb() const {
    return {Vec3(lower[0], lower[1], lower[2]), Vec3(upper[0], upper[1], upper[2])};
  }
  // Aabb::surfaceArea, term for term.
  float surfaceArea() const {
    if (lower[0] > upper[0] || lower[1] > upper[1] || lower[2] > upper[2]) return 0.0f;
    const Float4 e = upper - lower;
    return 2.0f * (e[0] * e[1] + e[1] * e[2] + e[2] * e[0]);
  }
};

// A primitive's box during the build, 32 bytes, moved by the partitions (the index travels in
// the order array beside it): the binning reads it without an indirection. The lower corner's
// unused fourth lane is 1 for a primitive tested on its own (kSingle), 0 for one tested in blocks.
constexpr float kSingle = 1.0f;
struct alignas(16) BuildBox {
  Float4 lower;
  Float4 upper;
  Float4 center() const { return 0.5f * (lower + upper); }  // Aabb::center
};

// What a node's primitives span: their boxes and their centres.
struct NodeExtent {
  Box4 box;
  Box4 centers;
};

// Boxes and primitive counts of every bin on every axis; `singles` of the counts are tested on
// their own.
struct Bins {
  Box4 boxes[3][kBinCount];
  uint32_t counts[3][kBinCount] = {};
  uint32_t singles[3][kBinCount] = {};

  // Min/max and sums: merging bins filled apart gives the same costs as filling them together
  // (a box's corner may differ only in the sign of a zero, which no area or comparison sees).
  void merge(const Bins& other) {
    for (int a = 0; a < 3; ++a) {
      for (int k = 0; k < kBinCount; ++k) {
        boxes[a][k].extend(other.boxes[a][k]);
        counts[a][k] += other.counts[a][k];
        singles[a][k] += other.singles[a][k];
      }
    }
  }
  // Bit k: bin k of axis a holds a primitive.
  uint32_t occupied(int a) const {
    uint32_t mask = 0;
    for (int k = 0; k < kBinCount; ++k) mask |= (counts[a][k] != 0 ? 1u : 0u) << k;
    return mask;
  }
};

// Ranges below this size are binned by one thread.
constexpr uint32_t kParallelBinningMinPrimitives = 65536;
// Below this size a second set of bins costs more to clear and merge than it saves.
constexpr uint32_t kTwoBinSetsMinPrimitives = 256;

struct Builder {
  BuildBox* boxes;
  uint32_t* order;
  std::vector<BvhNode>& nodes;
  BvhBuildStats& stats;
  uint32_t block = 1;
  int parallelLevels = 0;    // this many levels below the root build their right half on a thread
  int blockShift = -1;       // log2(block) when block is a power of two: no division per cost
  unsigned threads = 1;      // for the nodes above the parallel subtrees (the root on two cores)
  bool countSingles = true;  // some primitives are tested on their own, the rest in blocks

  float blocks(uint32_t count) const {
    const uint32_t rounded = count + block - 1;
    return static_cast<float>(blockShift >= 0 ? rounded >> blockShift : rounded / block);
  }
  // Tests a leaf of `count` primitives costs, `singles` of them tested on their own.
  float tests(uint32_t count, uint32_t singles) const {
    return blocks(count - singles) + static_cast<float>(singles);
  }

  uint32_t build(uint32_t begin, uint32_t end, const NodeExtent& extent, size_t depth) {
    const uint32_t nodeIndex = static_cast<uint32_t>(nodes.size());
    nodes.emplace_back();
    stats.maxDepth = std::max(stats.maxDepth, depth);
    nodes[nodeIndex].bounds = extent.box.aabb();
    const uint32_t count = end - begin;

    int axis = -1;
    uint32_t middle = begin;
    NodeExtent left, right;
    if (count > 1 && (depth < Bvh::kMaxDepth || count > kMaxLeafSize))
      chooseSplit(begin, end, extent, depth, axis, middle, left, right);
    if (axis < 0) {
      makeLeaf(nodeIndex, begin, count);
      return nodeIndex;
    }
    uint32_t second;
    if (static_cast<int>(depth) < parallelLevels && count >= kParallelMinPrimitives) {
      second = buildHalvesInParallel(begin, middle, end, left, right, depth);
    } else {
      build(begin, middle, left, depth + 1);
      second = build(middle, end, right, depth + 1);
    }
    nodes[nodeIndex].offset = second;
    nodes[nodeIndex].splitAxis = static_cast<uint8_t>(axis);
    return nodeIndex;
  }

  // The right half is built into its own array on another thread (the halves partition
  // disjoint ranges), then appended: the nodes come out exactly as a serial build lays them
  // out, so the tree does not depend on the number of threads.
  uint32_t buildHalvesInParallel(uint32_t begin, uint32_t middle, uint32_t end,
                                 const NodeExtent& left, const NodeExtent& right, size_t depth) {
    std::vector<BvhNode> rightNodes;
    reserveOnHugePages(rightNodes, 2 * (end - middle));
    BvhBuildStats rightStats;
    Builder rightBuilder{boxes,          order,      rightNodes, rightStats,  block,
                         parallelLevels, blockShift, threads,    countSingles};
    parallelFor(2, 2, [&](uint64_t half) {
      if (half == 0) {
        build(begin, middle, left, depth + 1);
      } else {
        rightBuilder.build(middle, end, right, depth + 1);
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

  // Bin of each axis's centre coordinate: trunc((c − lower) · scale) clamped to [0, 15], as a
  // scalar cast and clamp would give (lanes of axes without extent are never read).
  static Int4 binsOf(Float4 center, Float4 lower, Float4 scale) {
    Int4 bin = __builtin_convertvector((center - lower) * scale, Int4);
    bin = bin < 0 ? Int4{} : bin;
    const Int4 last = Int4{} + (kBinCount - 1);
    return bin > last ? last : bin;
  }

  template <bool kCountSingles>
  static void binOne(const BuildBox& b, Float4 lower, Float4 scale, Bins& bins) {
    const Int4 bin = binsOf(b.center(), lower, scale);
    for (int a = 0; a < 3; ++a) {
      Box4& target = bins.boxes[a][bin[a]];
      target.lower = simd::minLanes(b.lower, target.lower);
      target.upper = simd::maxLanes(b.upper, target.upper);
      ++bins.counts[a][bin[a]];
      if constexpr (kCountSingles) bins.singles[a][bin[a]] += b.lower[3] == kSingle;
    }
  }

  template <bool kCountSingles>
  void binRangeAs(uint32_t begin, uint32_t end, Float4 lower, Float4 scale, Bins& bins) const {
    if (end - begin < kTwoBinSetsMinPrimitives) {
      for (uint32_t i = begin; i < end; ++i) binOne<kCountSingles>(boxes[i], lower, scale, bins);
      return;
    }
    // Neighbouring primitives mostly fall into the same bins, and then each update waits for
    // the store of the one before: alternate primitives go to two sets, merged at the end.
    Bins odd;
    uint32_t i = begin;
    for (; i + 1 < end; i += 2) {
      binOne<kCountSingles>(boxes[i], lower, scale, bins);
      binOne<kCountSingles>(boxes[i + 1], lower, scale, odd);
    }
    if (i < end) binOne<kCountSingles>(boxes[i], lower, scale, bins);
    bins.merge(odd);
  }

  // Singles change a cost only when the others are tested in blocks of more than one.
  void binRange(uint32_t begin, uint32_t end, Float4 lower, Float4 scale, Bins& bins) const {
    if (countSingles) {
      binRangeAs<true>(begin, end, lower, scale, bins);
    } else {
      binRangeAs<false>(begin, end, lower, scale, bins);
    }
  }

  // Bins [begin, end) on every axis. The root's range is binned in two halves at once (the
  // halves below build in parallel anyway); merged in a fixed order, the bins are the same as one
  // thread's.
  void binAll(uint32_t begin, uint32_t end, size_t depth, Float4 lower, Float4 scale,
              Bins& bins) const {
    const uint32_t count = end - begin;
    const unsigned binThreads = depth == 0 ? std::min(threads, 2u) : 1u;
    if (binThreads > 1 && count >= kParallelBinningMinPrimitives) {
      Bins upper;
      const uint32_t half = begin + count / 2;
      parallelFor(2, 2, [&](uint64_t part) {
        if (part == 0) {
          binRange(begin, half, lower, scale, bins);
        } else {
          binRange(half, end, lower, scale, upper);
        }
      });
      bins.merge(upper);
    } else {
      binRange(begin, end, lower, scale, bins);
    }
  }

  // The SAH's cheapest split of axis a's bins, taken over (bestCost, bestAxis, bestBin) where
  // it costs less: the first of equal costs stays, as in a sweep over all axes in order.
  void bestSplitOnAxis(const Bins& bins, int a, float& bestCost, int& bestAxis,
                       int& bestBin) const {
    const auto& binBoxes = bins.boxes;
    const auto& binCounts = bins.counts;
    const auto& binSingles = bins.singles;
    // Only splits just above an occupied bin are candidates: a split above an empty bin
    // divides the primitives as the one below it does, costs the same, and the first of
    // equal costs is the one taken, so skipping those changes nothing.
    int occupied[kBinCount];
    int used = 0;
    for (uint32_t mask = bins.occupied(a); mask != 0; mask &= mask - 1) {
      occupied[used++] = __builtin_ctz(mask);
    }
    // Sweep from the right for the area and count of every right-hand side: rightArea[j]
    // for the primitives in occupied[j..].
    float rightArea[kBinCount];
    float rightTests[kBinCount];
    Box4 accumulated;
    uint32_t accumulatedCount = 0, accumulatedSingles = 0;
    for (int j = used - 1; j > 0; --j) {
      accumulated.extend(binBoxes[a][occupied[j]]);
      accumulatedCount += binCounts[a][occupied[j]];
      accumulatedSingles += binSingles[a][occupied[j]];
      rightArea[j] = accumulated.surfaceArea();
      rightTests[j] = tests(accumulatedCount, accumulatedSingles);
    }
    Box4 left;
    uint32_t leftCount = 0, leftSingles = 0;
    for (int j = 0; j + 1 < used; ++j) {
      left.extend(binBoxes[a][occupied[j]]);
      leftCount += binCounts[a][occupied[j]];
      leftSingles += binSingles[a][occupied[j]];
      const float cost =
          left.surfaceArea() * tests(leftCount, leftSingles) + rightArea[j + 1] * rightTests[j + 1];
      if (cost < bestCost) {
        bestCost = cost;
        bestAxis = a;
        bestBin = occupied[j] + 1;
      }
    }
  }

  // Picks the binned-SAH split and partitions [begin, end) by it, gathering what each side
  // spans on the way; axis = -1 when a leaf is cheaper (and allowed). One pass bins all three
  // axes; the costs, the chosen bin and the partition's order are those of the per-axis
  // original (Wald 2007; std::partition's two-ended swap).
  void chooseSplit(uint32_t begin, uint32_t end, const NodeExtent& node, size_t depth, int& axis,
                   uint32_t& middle, NodeExtent& leftOut, NodeExtent& rightOut) {
    const uint32_t count = end - begin;
    if (count <= kMaxLeafSize) {
      // A leaf that costs no more than visiting a node beats every split (which costs that
      // visit plus its children's tests), so it needs no binning.
      uint32_t leafSingles = 0;
      for (uint32_t i = begin; i < end; ++i) leafSingles += boxes[i].lower[3] == kSingle;
      if (kIntersectionCost * tests(count, leafSingles) <= kTraversalCost) return;
    }
    uint32_t singles = 0;  // primitives tested on their own, counted by the binning
    const Aabb centerBox = node.centers.aabb();
    const Vec3 extent = centerBox.extent();
    const Float4 lower = node.centers.lower;
    Float4 scale = {0.0f, 0.0f, 0.0f, 0.0f};
    bool anyAxis = false;
    for (int a = 0; a < 3; ++a) {
      if (!(extent[a] > 0.0f)) continue;
      scale[a] = kBinCount / extent[a];
      anyAxis = true;
    }
    float bestCost = kInf;
    int bestAxis = -1;
    int bestBin = 0;
    if (anyAxis) {
      Bins bins;
      binAll(begin, end, depth, lower, scale, bins);
      for (int b = 0; b < kBinCount; ++b) singles += bins.singles[0][b];  // each axis bins them all
      for (int a = 0; a < 3; ++a) {
        if (extent[a] > 0.0f) bestSplitOnAxis(bins, a, bestCost, bestAxis, bestBin);
      }
    }
    if (bestAxis < 0) {
      // Every centre coincides: no SAH split exists. Small sets become a leaf, large ones are
      // halved by index so a leaf never exceeds kMaxLeafSize.
      if (count > kMaxLeafSize) {
        axis = node.box.aabb().longestAxis();
        middle = begin + count / 2;
        leftOut = extentOf(begin, middle);
        rightOut = extentOf(middle, end);
      }
      return;
    }
    const float parentArea = std::max(node.box.surfaceArea(), 1e-30f);
    const float splitCost = kTraversalCost + kIntersectionCost * bestCost / parentArea;
    const float leafCost = kIntersectionCost * tests(count, singles);
    if (count <= kMaxLeafSize && splitCost >= leafCost) return;
    axis = bestAxis;
    middle = partition(begin, end, bestAxis, bestBin, lower, scale, leftOut, rightOut);
  }

  // Primitives whose centre falls in a bin below `splitBin` go left. Two ends moving inwards,
  // swapping misplaced pairs (the order std::partition leaves). Each primitive is classified
  // once, and added to the extent of its side then.
  uint32_t partition(uint32_t begin, uint32_t end, int splitAxis, int splitBin, Float4 lower,
                     Float4 scale, NodeExtent& left, NodeExtent& right) {
    const float axisLower = lower[splitAxis], axisScale = scale[splitAxis];
    const auto goesLeft = [&](uint32_t i) {
      const Float4 c = boxes[i].center();
      // The split axis's lane of binsOf, computed alone.
      const int bin = static_cast<int>((c[splitAxis] - axisLower) * axisScale);
      const bool isLeft = std::clamp(bin, 0, kBinCount - 1) < splitBin;
      NodeExtent& side = isLeft ? left : right;
      side.box.lower = simd::minLanes(boxes[i].lower, side.box.lower);
      side.box.upper = simd::maxLanes(boxes[i].upper, side.box.upper);
      side.centers.extendPoint(c);
      return isLeft;
    };
    uint32_t first = begin, last = end;
    for (;;) {
      for (;;) {
        if (first == last) return first;
        if (!goesLeft(first)) break;
        ++first;
      }
      --last;
      for (;;) {
        if (first == last) return first;
        if (goesLeft(last)) break;
        --last;
      }
      std::swap(boxes[first], boxes[last]);
      std::swap(order[first], order[last]);
      ++first;
    }
  }

  NodeExtent extentOf(uint32_t begin, uint32_t end) const {
    NodeExtent e;
    for (uint32_t i = begin; i < end; ++i) {
      e.box.lower = simd::minLanes(boxes[i].lower, e.box.lower);
      e.box.upper = simd::maxLanes(boxes[i].upper, e.box.upper);
      e.centers.extendPoint(boxes[i].center());
    }
    return e;
  }
};

}  // namespace

void Bvh::build(const std::vector<Aabb>& primitiveBounds, const BvhBuildOptions& options) {
  build(
      static_cast<uint32_t>(primitiveBounds.size()), [&](uint32_t i) { return primitiveBounds[i]; },
      options);
}

void Bvh::build(uint32_t count, const std::function<Aabb(uint32_t)>& boundsOf,
                const BvhBuildOptions& options) {
  const auto start = SteadyClock::now();
  nodes_.clear();
  order_.clear();
  reserveOnHugePages(order_, count);
  order_.resize(count);
  stats_ = {};
  for (uint32_t i = 0; i < order_.size(); ++i) order_[i] = i;
  if (count > 0) {
    const unsigned threads = std::max(1u, options.threads);
    // The builder's copy of the boxes and the root's extent, in two halves on two cores,
    // merged in a fixed order (min and max give the same extent either way).
    const std::unique_ptr<BuildBox[]> boxes(new BuildBox[count]);  // filled below, not zeroed
    preferHugePages(boxes.get(), count * sizeof(BuildBox));
    NodeExtent halves[2];
    const uint32_t middle = count / 2;
    parallelFor(2, count >= kParallelBinningMinPrimitives ? std::min(threads, 2u) : 1,
                [&](uint64_t part) {
                  const uint32_t begin = part == 0 ? 0 : middle, end = part == 0 ? middle : count;
                  NodeExtent& e = halves[part];
                  for (uint32_t i = begin; i < end; ++i) {
                    const Aabb b = boundsOf(i);
                    BuildBox& box = boxes[i];
                    const float single = i < options.blockedFrom ? kSingle : 0.0f;
                    box.lower = Float4{b.lower.x, b.lower.y, b.lower.z, single};
                    box.upper = Float4{b.upper.x, b.upper.y, b.upper.z, 0.0f};
                    e.box.lower = simd::minLanes(box.lower, e.box.lower);
                    e.box.upper = simd::maxLanes(box.upper, e.box.upper);
                    e.centers.extendPoint(box.center());
                  }
                });
    NodeExtent root = halves[0];
    root.box.extend(halves[1].box);
    root.centers.extend(halves[1].centers);
    // One level of threads per doubling of the cores, and two more: a split's halves are
    // seldom equal in work, so two cores build eight subtrees and neither waits for the other
    // (5 M triangles: first tile 1.7 -> 1.3 s on 2 cores).
    int levels = 0;
    for (unsigned cores = threads; cores > 1; cores /= 2) ++levels;
    if (levels > 0) levels += 2;
    const uint32_t block = std::max(1u, options.primitiveBlock);
    const int blockShift = (block & (block - 1)) == 0 ? __builtin_ctz(block) : -1;
    const bool countSingles = block > 1 && options.blockedFrom > 0;
    Builder builder{boxes.get(), order_.data(), nodes_,  stats_,      block,
                    levels,      blockShift,    threads, countSingles};
    reserveOnHugePages(nodes_, 2 * size_t{count});
    // Not shrunk to size afterwards: the reserved tail is never written, so it holds address
    // space but no memory, and a copy to size would fault in 62 MB more for 5 M triangles.
    builder.build(0, count, root, 0);
  }
  stats_.nodeCount = nodes_.size();
  stats_.memoryBytes = nodes_.size() * sizeof(BvhNode) + order_.size() * sizeof(uint32_t);
  stats_.seconds = secondsSince(start);
}

}  // namespace prism
