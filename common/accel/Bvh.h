// Bounding volume hierarchy over any set of bounded primitives, built with the surface-area
// heuristic (binned, after Wald, "On fast Construction of SAH-based Bounding Volume
// Hierarchies", 2007). The BVH knows only boxes; the caller intersects primitives in leaves.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include "math/Aabb.h"
#include "math/FloatError.h"
#include "util/Parallel.h"

namespace prism {
namespace wire {
template <class T>
struct Fields;
}

// 32 bytes, so two nodes share a cache line. Children of an interior node: the next node in
// the array, and secondChild.
struct BvhNode {
  Aabb bounds;
  uint32_t offset = 0;    // leaf: first entry in primitiveOrder; interior: second child index
  uint16_t count = 0;     // leaf: primitive count; interior: 0
  uint8_t splitAxis = 0;  // interior: axis the children were split along
  uint8_t padding = 0;
  bool isLeaf() const { return count > 0; }
};
static_assert(sizeof(BvhNode) == 32);

// How the SAH counts the cost of intersecting primitives. A leaf tested `primitiveBlock`
// primitives at a time (SIMD packs) costs the number of blocks, not of primitives, so the
// builder fills blocks instead of making leaves of one or two. Primitives below `blockedFrom`
// (the caller lists them first) are tested one at a time whatever the block: each costs one.
struct BvhBuildOptions {
  uint32_t primitiveBlock = 1;
  uint32_t blockedFrom = 0;
  // Threads the build may use; the tree is the same for any number.
  unsigned threads = static_cast<unsigned>(availableCores());
};

struct BvhBuildStats {
  double seconds = 0.0;
  size_t nodeCount = 0;
  size_t leafCount = 0;
  size_t maxDepth = 0;
  size_t memoryBytes = 0;  // nodes plus the primitive order
};

class Bvh {
 public:
  // SAH splits stop at this depth (bigger sets are still halved); the traversal stack is sized
  // for it with room for the rare halving below.
  static constexpr int kMaxDepth = 64;

  // Builds over the given boxes; empty input gives an empty BVH that nothing hits.
  void build(const std::vector<Aabb>& primitiveBounds, const BvhBuildOptions& options = {});
  // The same over `count` primitives whose boxes boundsOf(i) gives, so that the caller keeps no
  // array of them (5 M triangles' boxes are 120 MB). Called once per primitive, on several
  // threads at once.
  void build(uint32_t count, const std::function<Aabb(uint32_t)>& boundsOf,
             const BvhBuildOptions& options = {});

  // Leaf entries refer to primitiveOrder()[i]: the caller reorders its primitives to match.
  const std::vector<uint32_t>& primitiveOrder() const { return order_; }
  const std::vector<BvhNode>& nodes() const { return nodes_; }
  const BvhBuildStats& stats() const { return stats_; }
  Aabb bounds() const { return nodes_.empty() ? Aabb{} : nodes_[0].bounds; }

  // Visits the leaves the ray may hit, nearest child first. leafVisitor(first, count, tMax)
  // tests primitives first..first+count-1, shrinks tMax on a hit and returns true if it hit.
  // With anyHit the walk stops at the first leaf that reports a hit (shadow rays).
  template <class LeafVisitor>
  bool traverse(const Ray& ray, float& tMax, bool anyHit, LeafVisitor&& leafVisitor) const;

 private:
  template <class T>
  friend struct wire::Fields;  // the wire form lists the members (wire/GeometryCodec.h)

  std::vector<BvhNode> nodes_;
  std::vector<uint32_t> order_;
  BvhBuildStats stats_;
};

// Every slab test (binary, wide, packets) scales its far distances by this (Ize, "Robust BVH
// Ray Traversal", JCGT 2(2), 2013, as pbrt-v4 does): a slab distance (plane − o)·(1/d) carries
// three roundings, so a ray through a box's edge or corner could be told it misses a box it
// enters, and with it the triangles a watertight test would hit there.
inline constexpr float kSlabFarScale = 1.0f + 2.0f * gammaBound(3);

// Slab test returning the entry distance, or +inf when the ray misses the box within
// [tMin, tMax]. invDir may hold ±inf for axis-parallel rays.
inline float rayBoxEntry(const Aabb& box, const Vec3& origin, const Vec3& invDir, float tMin,
                         float tMax) {
  const Vec3 t0 = (box.lower - origin) * invDir;
  const Vec3 t1 = (box.upper - origin) * invDir;
  const Vec3 tNear = glm::min(t0, t1);
  const Vec3 tFar = glm::max(t0, t1) * kSlabFarScale;
  const float enter = std::max(std::max(tNear.x, tNear.y), std::max(tNear.z, tMin));
  const float leave = std::min(std::min(tFar.x, tFar.y), std::min(tFar.z, tMax));
  return enter <= leave ? enter : std::numeric_limits<float>::infinity();
}

template <class LeafVisitor>
bool Bvh::traverse(const Ray& ray, float& tMax, bool anyHit, LeafVisitor&& leafVisitor) const {
  if (nodes_.empty()) return false;
  const Vec3 invDir = 1.0f / ray.direction;
  constexpr float kMiss = std::numeric_limits<float>::infinity();
  if (rayBoxEntry(nodes_[0].bounds, ray.origin, invDir, ray.tMin, tMax) == kMiss) return false;
  // Each stack entry is a node whose box the ray enters, with its entry distance, so a node
  // that lies beyond a hit found meanwhile is skipped without testing its box again.
  struct Pending {
    uint32_t node;
    float entry;
  };
  Pending stack[2 * kMaxDepth];
  int stackSize = 0;
  uint32_t current = 0;
  bool hitAnything = false;
  for (;;) {
    const BvhNode& node = nodes_[current];
    if (node.isLeaf()) {
      if (leafVisitor(node.offset, node.count, tMax)) {
        hitAnything = true;
        if (anyHit) return true;
      }
    } else {
      // Test both children here; descend into the nearer, keep the farther for later.
      const uint32_t left = current + 1;
      const uint32_t right = node.offset;
      const float tLeft = rayBoxEntry(nodes_[left].bounds, ray.origin, invDir, ray.tMin, tMax);
      const float tRight = rayBoxEntry(nodes_[right].bounds, ray.origin, invDir, ray.tMin, tMax);
      if (tLeft != kMiss && tRight != kMiss) {
        if (tLeft <= tRight) {
          stack[stackSize++] = {right, tRight};
          current = left;
        } else {
          stack[stackSize++] = {left, tLeft};
          current = right;
        }
        continue;
      }
      if (tLeft != kMiss) {
        current = left;
        continue;
      }
      if (tRight != kMiss) {
        current = right;
        continue;
      }
    }
    // Pop the next pending node that still starts before the closest hit.
    do {
      if (stackSize == 0) return hitAnything;
      --stackSize;
    } while (stack[stackSize].entry > tMax);
    current = stack[stackSize].node;
  }
}

}  // namespace prism
