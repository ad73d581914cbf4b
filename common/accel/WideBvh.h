// An 8-wide BVH collapsed from the binary SAH BVH (accel/Bvh.h): each node holds the boxes of up
// to eight children in structure-of-arrays form, so one ray tests all eight with a few SIMD
// instructions (math/Simd.h). The collapse keeps the binary BVH's leaves and primitive order,
// so the same leaf visitor serves both, and the closest hit is the same primitive test.
//
// Collapsing: starting from a binary node, the child with the largest surface area that is not a
// leaf is replaced by its two children until eight slots are used (after Wald et al., "Getting
// Rid of Packets", 2008, and Embree's BVH8 built the same way from a binary SAH build). A child
// with at most eight leaves below it is opened only if all of them fit in the node; otherwise
// it becomes one node of its own, rather than several half-empty ones.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "accel/Bvh.h"
#include "math/Simd.h"

namespace prism {
namespace wire {
template <class T>
struct Fields;
}

struct alignas(64) WideBvhNode {
  static constexpr int kWidth = 8;
  // bounds[2 * axis] is the lower, bounds[2 * axis + 1] the upper plane of each child. Unused
  // slots hold an inverted box (lower +inf, upper -inf) that no ray enters.
  float bounds[6][kWidth];
  uint32_t child[kWidth];  // interior child: node index; leaf child: first primitive entry
  uint8_t count[kWidth];   // leaf child: primitive count (> 0); interior child or unused: 0
  // What alignment would pad, named and zeroed: a node's memory is then its wire form, every
  // byte defined (wire/GeometryCodec.h copies nodes in one go).
  uint8_t unused[24] = {};
};
static_assert(sizeof(WideBvhNode) == 256);

// The vector a node's slab test works on: all eight children at once with AVX, four (two
// halves a node) otherwise.
#if defined(__AVX__)
using SlabLanes = simd::Float8;
#else
using SlabLanes = simd::Float4;
#endif

// What a ray needs for the slab test of every node: which plane of each axis it meets first, and
// its origin, reciprocal direction and tMin broadcast to every lane, made once a walk. The walk
// calls its leaf visitor between node tests, and a call clobbers every vector register; node
// tests that broadcast these again after each took 122 instructions where they now take 75
// (docs/journal/2026-11-27-node-test-broadcasts.md).
struct WideRay {
  int nearSide[3];  // 0: lower plane first (direction >= +0), 1: upper plane first
  SlabLanes originLanes[3];
  SlabLanes invDirLanes[3];
  SlabLanes tMinLanes;
  SlabLanes farScaleLanes;  // kSlabFarScale

  explicit WideRay(const Ray& ray) {
    for (int a = 0; a < 3; ++a) {
      const float invDir = 1.0f / ray.direction[a];
      nearSide[a] = std::signbit(invDir) ? 1 : 0;  // -0 gives -inf: upper plane first
      originLanes[a] = simd::broadcast<SlabLanes>(ray.origin[a]);
      invDirLanes[a] = simd::broadcast<SlabLanes>(invDir);
    }
    tMinLanes = simd::broadcast<SlabLanes>(ray.tMin);
    farScaleLanes = simd::broadcast<SlabLanes>(kSlabFarScale);
  }
};

// Entry distances of the children a ray enters within [ray's tMin, tMax] (bit i of the result);
// the other entries are unspecified. NaN (a ray in a slab's plane, parallel to it) counts as
// entering, so the test never rejects a box the scalar test would accept. Without AVX the node's
// two halves go axis by axis side by side, so each plane's two loads share one address.
inline uint32_t intersectChildren(const WideBvhNode& node, const WideRay& ray,
                                  const SlabLanes& tMax, float entry[WideBvhNode::kWidth]) {
  using V = SlabLanes;
  constexpr int kHalves = WideBvhNode::kWidth / (sizeof(V) / sizeof(float));
  constexpr int kLanes = sizeof(V) / sizeof(float);
  V enter[kHalves], leave[kHalves];
  for (int h = 0; h < kHalves; ++h) {
    enter[h] = ray.tMinLanes;
    leave[h] = tMax;
  }
  for (int a = 0; a < 3; ++a) {
    const float* nearPlanes = node.bounds[2 * a + ray.nearSide[a]];
    const float* farPlanes = node.bounds[2 * a + 1 - ray.nearSide[a]];
    for (int h = 0; h < kHalves; ++h) {
      const V nearPlane = simd::load<V>(nearPlanes + h * kLanes);
      const V farPlane = simd::load<V>(farPlanes + h * kLanes);
      // The slab distances go first: a NaN there leaves enter and leave as they were.
      enter[h] = simd::maxLanes((nearPlane - ray.originLanes[a]) * ray.invDirLanes[a], enter[h]);
      leave[h] = simd::minLanes(
          (farPlane - ray.originLanes[a]) * ray.invDirLanes[a] * ray.farScaleLanes, leave[h]);
    }
  }
  uint32_t mask = 0;
  for (int h = 0; h < kHalves; ++h) {
    std::memcpy(entry + h * kLanes, &enter[h], sizeof(V));
    mask |= simd::laneMask(enter[h] <= leave[h]) << (h * kLanes);
  }
  return mask;
}

// The same slab test one child at a time, for testing the SIMD path against.
uint32_t intersectChildrenScalar(const WideBvhNode& node, const Ray& ray, float tMin, float tMax,
                                 float entry[WideBvhNode::kWidth]);

struct WideBvhStats {
  size_t nodeCount = 0;
  size_t memoryBytes = 0;  // wide nodes only (the primitive order belongs to the binary BVH)
  double seconds = 0.0;
};

class WideBvh {
 public:
  // Collapses the given binary BVH; an empty one gives an empty wide BVH that nothing hits.
  void build(const Bvh& binary);

  const std::vector<WideBvhNode>& nodes() const { return nodes_; }

  // Lets the caller give leaves its own numbering: relabel(first, count) returns the (child,
  // count) the leaf visitor will receive instead, count staying in 1..255. The scene points
  // leaves straight at its triangle packs this way, saving a lookup per leaf.
  template <class Relabel>
  void relabelLeaves(Relabel&& relabel) {
    for (WideBvhNode& node : nodes_) {
      for (int i = 0; i < WideBvhNode::kWidth; ++i) {
        if (node.count[i] == 0) continue;
        const auto [child, count] = relabel(node.child[i], node.count[i]);
        node.child[i] = child;
        node.count[i] = static_cast<uint8_t>(count);
      }
    }
  }
  const WideBvhStats& stats() const { return stats_; }

  // False only if the ray misses, within [ray.tMin, tMax], the box around the root's children,
  // so that no walk could enter any of them: a test of a few instructions a shadow ray may take
  // before a walk's set-up and root test. True at once for a ray starting inside the box (which
  // the test could not reject). Same answers as walking: it never rejects what the walk enters.
  bool entersTree(const Ray& ray, float tMax) const;

  // Same contract as Bvh::traverse: leafVisitor(first, count, tMax) tests primitives
  // first..first+count-1, shrinks tMax on a hit and returns true if it hit. Closest-hit walks
  // visit children nearest first; any-hit walks skip the sort and stop at the first hit.
  template <bool kAnyHit, class LeafVisitor>
  bool traverse(const Ray& ray, float& tMax, LeafVisitor&& leafVisitor) const;

 private:
  template <class T>
  friend struct wire::Fields;  // the wire form lists the members (wire/GeometryCodec.h)

  std::vector<WideBvhNode> nodes_;
  Aabb rootBounds_;  // the binary root's box, around the root's children; empty for an empty tree
  WideBvhStats stats_;
};

template <bool kAnyHit, class LeafVisitor>
bool WideBvh::traverse(const Ray& ray, float& tMax, LeafVisitor&& leafVisitor) const {
  if (nodes_.empty()) return false;
  const WideRay wide(ray);
  struct Pending {
    uint32_t child;
    uint32_t count;  // 0: interior node
    float entry;
  };
  // Each level of the walk leaves at most seven entries behind; the depth is at most the binary
  // BVH's, which is at most 2 * kMaxDepth (see Bvh::traverse).
  Pending stack[WideBvhNode::kWidth * 2 * Bvh::kMaxDepth];
  int stackSize = 0;
  Pending current{0, 0, ray.tMin};
  SlabLanes tMaxLanes = simd::broadcast<SlabLanes>(tMax);  // tMax changes only at a hit
  bool hitAnything = false;
  for (;;) {
    if (current.count > 0) {
      if (leafVisitor(current.child, current.count, tMax)) {
        hitAnything = true;
        if constexpr (kAnyHit) return true;
        tMaxLanes = simd::broadcast<SlabLanes>(tMax);
      }
    } else {
      const WideBvhNode& node = nodes_[current.child];
      float entry[WideBvhNode::kWidth];
      uint32_t mask = intersectChildren(node, wide, tMaxLanes, entry);
      if (mask != 0) {
        int i = simd::firstLane(mask);
        mask &= mask - 1;
        if (mask == 0) {  // one child entered, the common case deep in the tree: no stack
          current = {node.child[i], node.count[i], entry[i]};
          continue;
        }
        // Several children: go on with the one the stack would give next and push the others,
        // so the next node's address does not wait on a store and a load of the stack. Any-hit
        // walks take the last lane; closest-hit walks the nearest, the later lane on a tie, and
        // keep the rest sorted (an entered child's entry always lies within tMax).
        mask |= 1u << i;
        int next = i;
        for (uint32_t rest = mask & (mask - 1); rest != 0; rest &= rest - 1) {
          const int lane = simd::firstLane(rest);
          if (kAnyHit || !(entry[next] < entry[lane])) next = lane;
        }
        const int base = stackSize;
        for (mask &= ~(1u << next); mask != 0; mask &= mask - 1) {
          i = simd::firstLane(mask);
          const Pending incoming{node.child[i], node.count[i], entry[i]};
          if constexpr (kAnyHit) {
            stack[stackSize++] = incoming;  // any hit will do: no order needed
          } else {
            // Insertion sort, descending by entry distance, so the nearest is popped first.
            int at = stackSize++;
            while (at > base && stack[at - 1].entry < incoming.entry) {
              stack[at] = stack[at - 1];
              --at;
            }
            stack[at] = incoming;
          }
        }
        current = {node.child[next], node.count[next], entry[next]};
        continue;
      }
    }
    // Pop the next pending child that still starts before the closest hit.
    do {
      if (stackSize == 0) return hitAnything;
      current = stack[--stackSize];
    } while (current.entry > tMax);
  }
}

}  // namespace prism
