#include "accel/WideBvh.h"

#include <algorithm>
#include <cmath>

#include "util/HugePages.h"
#include "util/Stopwatch.h"

namespace prism {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// A child slot during the collapse: a binary node to be placed in a wide node.
struct Slot {
  uint32_t binaryNode;
  float area;
};

}  // namespace

uint32_t intersectChildrenScalar(const WideBvhNode& node, const Ray& ray, float tMin, float tMax,
                                 float entry[WideBvhNode::kWidth]) {
  uint32_t mask = 0;
  for (int i = 0; i < WideBvhNode::kWidth; ++i) {
    float enter = tMin, leave = tMax;
    for (int a = 0; a < 3; ++a) {
      const float inv = 1.0f / ray.direction[a];
      const int nearSide = std::signbit(inv) ? 1 : 0;
      const float tNear = (node.bounds[2 * a + nearSide][i] - ray.origin[a]) * inv;
      const float tFar =
          (node.bounds[2 * a + 1 - nearSide][i] - ray.origin[a]) * inv * kSlabFarScale;
      enter = tNear > enter ? tNear : enter;
      leave = tFar < leave ? tFar : leave;
    }
    entry[i] = enter;
    if (enter <= leave) mask |= 1u << i;
  }
  return mask;
}

bool WideBvh::entersTree(const Ray& ray, float tMax) const {
  if (rootBounds_.empty()) return false;
  if (rootBounds_.contains(ray.origin)) return true;
  // intersectChildrenScalar's arithmetic on the box around the children: each slab distance of
  // the box lies on the permissive side of the same distance for every child (the roundings are
  // monotonic, and a NaN, which the tests ignore, can only appear here where a child has one
  // too or lies further in), so a ray this test rejects is rejected by every child's test.
  float enter = ray.tMin, leave = tMax;
  for (int a = 0; a < 3; ++a) {
    const float inv = 1.0f / ray.direction[a];
    const bool upperFirst = std::signbit(inv);
    const float nearPlane = upperFirst ? rootBounds_.upper[a] : rootBounds_.lower[a];
    const float farPlane = upperFirst ? rootBounds_.lower[a] : rootBounds_.upper[a];
    const float tNear = (nearPlane - ray.origin[a]) * inv;
    const float tFar = (farPlane - ray.origin[a]) * inv * kSlabFarScale;
    enter = tNear > enter ? tNear : enter;
    leave = tFar < leave ? tFar : leave;
  }
  return enter <= leave;
}

void WideBvh::build(const Bvh& binary) {
  const auto start = SteadyClock::now();
  nodes_.clear();
  stats_ = {};
  const std::vector<BvhNode>& bin = binary.nodes();
  if (!bin.empty()) {
    reserveOnHugePages(nodes_, bin.size() / 4 + 1);
    // Leaves under each binary node (a node's children come after it in the array).
    HugePageVector<uint32_t> leaves(bin.size());
    for (size_t i = bin.size(); i-- > 0;) {
      leaves[i] = bin[i].isLeaf() ? 1 : leaves[i + 1] + leaves[bin[i].offset];
    }
    // Work list of (binary node, wide node index) pairs still to be filled.
    std::vector<std::pair<uint32_t, uint32_t>> work{{0, 0}};
    nodes_.emplace_back();
    while (!work.empty()) {
      const auto [binaryIndex, wideIndex] = work.back();
      work.pop_back();
      Slot slots[WideBvhNode::kWidth];
      int used = 0;
      if (bin[binaryIndex].isLeaf()) {
        slots[used++] = {binaryIndex, 0.0f};  // the whole BVH is one leaf
      } else {
        const uint32_t first = binaryIndex + 1, second = bin[binaryIndex].offset;
        slots[used++] = {first, bin[first].bounds.surfaceArea()};
        slots[used++] = {second, bin[second].bounds.surfaceArea()};
      }
      // Open the largest interior slot until the node is full or only leaves remain. A subtree
      // of at most kWidth leaves is opened only if all of them fit here: otherwise it becomes one
      // full node of its own instead of several half-empty ones.
      while (used < WideBvhNode::kWidth) {
        int largest = -1;
        for (int i = 0; i < used; ++i) {
          const uint32_t node = slots[i].binaryNode;
          if (bin[node].isLeaf()) continue;
          const bool small = leaves[node] <= WideBvhNode::kWidth;
          if (small && used - 1 + static_cast<int>(leaves[node]) > WideBvhNode::kWidth) continue;
          if (largest < 0 || slots[i].area > slots[largest].area) largest = i;
        }
        if (largest < 0) break;
        const uint32_t opened = slots[largest].binaryNode;
        const uint32_t first = opened + 1, second = bin[opened].offset;
        slots[largest] = {first, bin[first].bounds.surfaceArea()};
        slots[used++] = {second, bin[second].bounds.surfaceArea()};
      }
      WideBvhNode filled;
      for (int i = 0; i < WideBvhNode::kWidth; ++i) {
        filled.child[i] = 0;
        filled.count[i] = 0;
        for (int a = 0; a < 3; ++a) {
          filled.bounds[2 * a][i] = kInf;
          filled.bounds[2 * a + 1][i] = -kInf;
        }
      }
      for (int i = 0; i < used; ++i) {
        const BvhNode& b = bin[slots[i].binaryNode];
        for (int a = 0; a < 3; ++a) {
          filled.bounds[2 * a][i] = b.bounds.lower[a];
          filled.bounds[2 * a + 1][i] = b.bounds.upper[a];
        }
        if (b.isLeaf()) {
          filled.child[i] = b.offset;
          filled.count[i] = static_cast<uint8_t>(b.count);
        } else {
          filled.child[i] = static_cast<uint32_t>(nodes_.size());
          work.push_back({slots[i].binaryNode, filled.child[i]});
          nodes_.emplace_back();
        }
      }
      nodes_[wideIndex] = filled;
    }
  }
  // For entersTree: the binary root's box, which holds every node's (boxes are unions).
  rootBounds_ = bin.empty() ? Aabb() : bin[0].bounds;
  stats_.nodeCount = nodes_.size();
  stats_.memoryBytes = nodes_.size() * sizeof(WideBvhNode);
  stats_.seconds = secondsSince(start);
}

}  // namespace prism
