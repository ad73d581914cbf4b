// Packet traversal of the wide BVH for coherent rays (a pixel tile's primary rays, their shadow
// rays): the packet walks the tree as one ray, testing each node's eight child boxes with one
// SIMD slab test in interval arithmetic over the packet's origins and reciprocal directions
// (after Boulos et al., "Geometric and Arithmetic Culling Methods for Entire Ray Packets",
// 2006). The test is conservative: a box any ray of the packet enters passes, so every ray
// still meets every leaf it would meet alone, and the caller's leaf visitor tests the rays one
// by one. Packets whose directions differ in sign on some axis take the single-ray walk.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

#include "accel/WideBvh.h"

namespace prism {

struct RayPacket8 {
  static constexpr int kSize = 8;
  // Largest difference of unit-direction components within a coherent packet: a 4 × 2 pixel
  // block of a camera differs by about 0.01, shadow rays towards one light by little more.
  static constexpr float kMaxDirectionSpread = 0.1f;
  // Largest spread of the origins along an axis, as a fraction of the packet's shortest ray
  // (rays of finite length: shadow rays). Shadow rays from a 4 × 2 pixel block on one surface
  // spread by about a hundredth of their length (the default scene's floor at 640 × 360; less at
  // higher resolutions); a block whose hits lie on different objects far apart spreads by much
  // more, and the interval test would then admit every box between them. 0.01 to 0.03 measured
  // alike (docs/journal/2026-11-26-packets-whose-origins-lie-far-apart.md).
  static constexpr float kMaxOriginSpread = 0.02f;
  // Per axis, the bounds of the packet's origins and reciprocal directions.
  float originLow[3], originHigh[3], invLow[3], invHigh[3];
  int nearSide[3];  // as in WideRay: 1 when every direction is negative on that axis
  bool coherent;    // every axis has one direction sign and finite origins and reciprocals
  float tMin;       // the smallest tMin of the rays
  // Each ray's own origin, direction, reciprocal direction, tMin and tMax, for the per-ray tests
  // of leaf boxes and triangles. Lanes of dead rays repeat the first live ray, so bounds taken
  // over all eight lanes are the live rays' bounds.
  alignas(32) float rayOrigin[3][kSize];
  alignas(32) float rayDirection[3][kSize];
  alignas(32) float rayInvDir[3][kSize];
  alignas(32) float rayTMin[kSize];
  alignas(32) float rayTMax[kSize];

  // live (bit i: rays[i]) must not be empty.
  RayPacket8(const Ray* rays, uint32_t live) {
    using simd::Float4;
    using simd::load;
    static_assert(sizeof(Ray) == 8 * sizeof(float) && offsetof(Ray, tMax) == 7 * sizeof(float));
    // Each ray is two rows of four floats (origin, direction x; direction y, z, tMin, tMax);
    // four rays' rows transposed in registers give the columns. Writing the floats one by one
    // and reading them four at a time would stall every read on its stores.
    const int fill = simd::firstLane(live);  // live is not empty (the callers return first)
    for (int at = 0; at < kSize; at += 4) {
      Float4 row[2][4];
      for (int k = 0; k < 4; ++k) {
        const int i = at + k;
        const float* ray = reinterpret_cast<const float*>(&rays[(live >> i & 1u) ? i : fill]);
        row[0][k] = load<Float4>(ray);
        row[1][k] = load<Float4>(ray + 4);
      }
      simd::transpose(row[0][0], row[0][1], row[0][2], row[0][3]);
      simd::transpose(row[1][0], row[1][1], row[1][2], row[1][3]);
      for (int a = 0; a < 3; ++a) simd::store(&rayOrigin[a][at], row[0][a]);
      simd::store(&rayDirection[0][at], row[0][3]);
      simd::store(&rayDirection[1][at], row[1][0]);
      simd::store(&rayDirection[2][at], row[1][1]);
      simd::store(&rayTMin[at], row[1][2]);
      simd::store(&rayTMax[at], row[1][3]);
    }
    coherent = live != 0;
    tMin = lowest(load<Float4>(&rayTMin[0]), load<Float4>(&rayTMin[4]));
    // Infinite for rays without an end (camera rays, bounces): no limit on their origins.
    const float originLimit =
        kMaxOriginSpread * lowest(load<Float4>(&rayTMax[0]), load<Float4>(&rayTMax[4]));
    for (int a = 0; a < 3; ++a) {
      const Float4 d0 = load<Float4>(&rayDirection[a][0]), d1 = load<Float4>(&rayDirection[a][4]);
      // The same correctly rounded division as WideRay's, four lanes at a time.
      const Float4 inv0 = 1.0f / d0, inv1 = 1.0f / d1;
      simd::store(&rayInvDir[a][0], inv0);
      simd::store(&rayInvDir[a][4], inv1);
      const Float4 o0 = load<Float4>(&rayOrigin[a][0]), o1 = load<Float4>(&rayOrigin[a][4]);
      originLow[a] = lowest(o0, o1);
      originHigh[a] = highest(o0, o1);
      invLow[a] = lowest(inv0, inv1);
      invHigh[a] = highest(inv0, inv1);
      // x - x is 0 for finite x and NaN for infinities and NaN: such rays take the single walk.
      const uint32_t finite = simd::laneMask((o0 - o0 == 0.0f) & (inv0 - inv0 == 0.0f)) |
                              simd::laneMask((o1 - o1 == 0.0f) & (inv1 - inv1 == 0.0f)) << 4;
      // A finite reciprocal is never zero, so its sign bit is (inv < 0).
      const uint32_t negative = simd::laneMask(inv0 < 0.0f) | simd::laneMask(inv1 < 0.0f) << 4;
      if (finite != 0xFFu || (negative != 0 && negative != 0xFFu)) coherent = false;
      // Spread-out directions make the interval test pass nearly everywhere: such packets
      // would walk most of the tree, so they take the single-ray walk instead.
      if (highest(d0, d1) - lowest(d0, d1) > kMaxDirectionSpread) coherent = false;
      // So do packets whose origins lie far apart for their length (see kMaxOriginSpread).
      if (originHigh[a] - originLow[a] > originLimit) coherent = false;
      nearSide[a] = negative != 0 ? 1 : 0;
    }
  }

 private:
  static float lowest(simd::Float4 a, simd::Float4 b) {
    const simd::Float4 m = simd::minLanes(a, b);
    return std::min(std::min(m[0], m[1]), std::min(m[2], m[3]));
  }
  static float highest(simd::Float4 a, simd::Float4 b) {
    const simd::Float4 m = simd::maxLanes(a, b);
    return std::max(std::max(m[0], m[1]), std::max(m[2], m[3]));
  }
};

// Children (bit i) that some ray of the packet may enter within [packet.tMin, tMax], with a
// lower bound of the entry distance. For an axis, the distance to a plane is (plane - o) * inv
// with o and inv in intervals; its bounds are the extreme products of the interval ends, and
// float rounding is monotone, so each ray's own slab distances lie within them. V
// (simd::Float4 or Float8) is how many children one vector tests; the answer is the same.
template <class V>
inline uint32_t packetEntersChildren(const WideBvhNode& node, const RayPacket8& packet, float tMax,
                                     float entry[WideBvhNode::kWidth]) {
  constexpr int kLanes = sizeof(V) / sizeof(float);
  uint32_t mask = 0;
  for (int at = 0; at < WideBvhNode::kWidth; at += kLanes) {
    V enter = simd::broadcast<V>(packet.tMin);
    V leave = simd::broadcast<V>(tMax);
    for (int a = 0; a < 3; ++a) {
      const V nearPlane = simd::load<V>(&node.bounds[2 * a + packet.nearSide[a]][at]);
      const V farPlane = simd::load<V>(&node.bounds[2 * a + 1 - packet.nearSide[a]][at]);
      const V invLow = simd::broadcast<V>(packet.invLow[a]);
      const V invHigh = simd::broadcast<V>(packet.invHigh[a]);
      // Near plane: the smallest product; far plane: the largest.
      const V nearA = nearPlane - simd::broadcast<V>(packet.originHigh[a]);
      const V nearB = nearPlane - simd::broadcast<V>(packet.originLow[a]);
      const V tNear = simd::minLanes(simd::minLanes(nearA * invLow, nearA * invHigh),
                                     simd::minLanes(nearB * invLow, nearB * invHigh));
      const V farA = farPlane - simd::broadcast<V>(packet.originHigh[a]);
      const V farB = farPlane - simd::broadcast<V>(packet.originLow[a]);
      const V tFar = simd::maxLanes(simd::maxLanes(farA * invLow, farA * invHigh),
                                    simd::maxLanes(farB * invLow, farB * invHigh)) *
                     kSlabFarScale;
      enter = simd::maxLanes(tNear, enter);
      leave = simd::minLanes(tFar, leave);
    }
    simd::store(entry + at, enter);
    mask |= simd::laneMask(enter <= leave) << at;
  }
  return mask;
}

// The rays (bit i) that enter child `slot` of the node within their own [tMin, tMax]: the
// single-ray slab test, a vector V of rays at a time. Run on leaves only, so that a leaf is tested
// against just the rays that reach it.
template <class V>
inline uint32_t raysEnteringChild(const WideBvhNode& node, int slot, const RayPacket8& packet,
                                  const float tMax[RayPacket8::kSize]) {
  constexpr int kLanes = sizeof(V) / sizeof(float);
  uint32_t mask = 0;
  for (int at = 0; at < RayPacket8::kSize; at += kLanes) {
    V enter = simd::load<V>(&packet.rayTMin[at]);
    V leave = simd::load<V>(&tMax[at]);
    for (int a = 0; a < 3; ++a) {
      const V origin = simd::load<V>(&packet.rayOrigin[a][at]);
      const V invDir = simd::load<V>(&packet.rayInvDir[a][at]);
      const V nearPlane = simd::broadcast<V>(node.bounds[2 * a + packet.nearSide[a]][slot]);
      const V farPlane = simd::broadcast<V>(node.bounds[2 * a + 1 - packet.nearSide[a]][slot]);
      enter = simd::maxLanes((nearPlane - origin) * invDir, enter);
      leave = simd::minLanes((farPlane - origin) * invDir * kSlabFarScale, leave);
    }
    mask |= simd::laneMask(enter <= leave) << at;
  }
  return mask;
}

// Walks the tree with the rays in `live` (the packet must be coherent). leafVisitor(first,
// count, rays, tMax) tests the leaf against the rays in the mask `rays`, shrinks their tMax on
// hits and returns the mask of rays it hit. Returns the rays that hit anything; any-hit walks
// stop testing a ray at its first hit. V: the vector of the box tests (the answers do not
// depend on it).
template <bool kAnyHit, class V, class LeafVisitor>
uint32_t traversePacket(const WideBvh& bvh, const RayPacket8& packet, uint32_t live,
                        float tMax[RayPacket8::kSize], LeafVisitor&& leafVisitor) {
  const std::vector<WideBvhNode>& nodes = bvh.nodes();
  if (nodes.empty() || live == 0) return 0;
  struct Pending {
    uint32_t child;
    uint32_t count;  // 0: interior node
    float entry;
    uint32_t rays;  // leaf: the rays that enter its box
  };
  // The largest tMax of the rays still looking: nodes beyond it are skipped.
  auto farthest = [&](uint32_t rays) {
    float t = -std::numeric_limits<float>::infinity();
    for (; rays != 0; rays &= rays - 1) t = std::max(t, tMax[simd::firstLane(rays)]);
    return t;
  };
  Pending stack[WideBvhNode::kWidth * 2 * Bvh::kMaxDepth];
  int stackSize = 0;
  Pending current{0, 0, packet.tMin, 0};
  uint32_t hitRays = 0;
  uint32_t looking = live;
  float reach = farthest(looking);
  for (;;) {
    if (current.count > 0) {
      const uint32_t rays = current.rays & looking;
      const uint32_t hits = rays ? leafVisitor(current.child, current.count, rays, tMax) : 0u;
      hitRays |= hits;
      if (kAnyHit) {
        looking &= ~hits;
        if (looking == 0) return hitRays;
      }
      if (hits != 0) reach = farthest(looking);
    } else {
      const WideBvhNode& node = nodes[current.child];
      float entry[WideBvhNode::kWidth];
      uint32_t mask = packetEntersChildren<V>(node, packet, reach, entry);
      const int base = stackSize;
      for (; mask != 0; mask &= mask - 1) {
        const int i = simd::firstLane(mask);
        uint32_t rays = 0;
        if (node.count[i] > 0) {
          rays = raysEnteringChild<V>(node, i, packet, tMax) & looking;
          if (rays == 0) continue;
        }
        const Pending incoming{node.child[i], node.count[i], entry[i], rays};
        int at = stackSize++;
        while (!kAnyHit && at > base && stack[at - 1].entry < incoming.entry) {
          stack[at] = stack[at - 1];
          --at;
        }
        stack[at] = incoming;
      }
    }
    do {
      if (stackSize == 0) return hitRays;
      current = stack[--stackSize];
    } while (current.entry > reach);
  }
}

}  // namespace prism
