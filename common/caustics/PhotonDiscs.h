// Photons as discs of their own radius, for the sample-point density estimate (Breiman, Meisel &
// Purcell 1977; in photon mapping, "photon splatting"): each photon spreads its power over a
// kernel of its own radius, so the estimate integrates to exactly the photons' power, whatever
// the radii. A bounding-volume tree over the discs' boxes answers "which discs cover x".
// Built the same from the same photons and radii on every rank, and visited in the same order.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "caustics/Photon.h"
#include "math/RayDifferential.h"
#include "math/Simd.h"

namespace prism {

class PhotonDiscs {
 public:
  // A photon as a gather reads it: kept in tree order with its squared radius and its direction
  // decoded once (Photon::directionVector()'s very floats). A gather then reads the photons it
  // visits one after another, where looking each up in the map's order cost a cache miss and
  // decoding it a square root and a division: most of a gather's time with millions of photons.
  struct Disc {
    Vec3 position;
    float radius2;
    Color power;
    Vec3 direction;
    const Vec3& directionVector() const { return direction; }
  };

  // radii[i] is photon i's radius (> 0). Built on up to `threads` threads (0: all cores); the
  // tree is the same for any count.
  PhotonDiscs(const std::vector<Photon>& photons, const std::vector<float>& radii, int threads = 0);

  // Calls visit(disc, squared distance, squared radius) for every photon whose disc covers x
  // (distance < radius), in tree order.
  template <class Visit>
  void covering(const Vec3& x, Visit&& visit) const;
  // The same for every photon of squared radius at most max2 whose disc comes within reach of x
  // (distance < radius + reach: it may cover part of a pixel's footprint; PhotonGather), less
  // photons of squared radius at most narrow2 whose centre x + q fails inFootprint.contains(q):
  // those count nothing (PhotonGather passes the footprint grown by the narrow photons' largest
  // radius: a narrow photon counts only where its disc meets the footprint). Subtrees without a
  // photon to visit are skipped at once: at grazing angles the footprint is a sliver of the ball of
  // its reach, which held 9 in 10 of the photons tested.
  template <class Visit>
  void reaching(const Vec3& x, float reach, float max2, float narrow2,
                const PixelFootprint::Test& inFootprint, Visit&& visit) const;

 private:
  // A node of the binary tree the build makes: the discs' boxes below it and where its children
  // or slots are. The walks use the 4-wide tree made from it (Wide).
  struct Node {
    Vec3 lo, hi;     // bounds of the discs' boxes below
    uint32_t first;  // leaf: first slot; interior: index of the second child (the first follows)
    uint8_t count;   // leaf: slots (at most 8, or 4 at the depth limit); interior: 0
    // The largest squared radius below, as its float's exponent field: the power of two above
    // it is an upper bound.
    uint8_t maxRadius2Exponent;
    // The smallest squared radius below, as the top 16 bits of its float (rounded down: a lower
    // bound), so that a node stays 32 bytes.
    uint16_t minRadius2Bits;
  };
  static_assert(sizeof(Node) == 32);
  // Two levels of the binary tree as one node: up to four entries (a binary node's
  // grandchildren, or a child that is a leaf), in the binary tree's depth-first order, their
  // bounds as columns so that one vector test answers for all four. Every entry's test is the
  // binary node's own, and a node is entered only where its parent's test passed, so the walks
  // visit the very slots, in the very order, the binary walks did, with fewer branches and node
  // loads: a caustic frame 4–6 % faster (docs/journal/2026-11-28-budgets-and-the-regular-part.md).
  struct Wide {
    float loX[4], loY[4], loZ[4], hiX[4], hiY[4], hiZ[4];
    uint32_t child[4];  // leaf: first slot; interior: the Wide node's index
    uint8_t count[4];   // leaf: slots; interior, or no entry: 0
    uint8_t maxRadius2Exponent[4];
    uint16_t minRadius2Bits[4];
    Vec3 lo(int k) const { return {loX[k], loY[k], loZ[k]}; }
    Vec3 hi(int k) const { return {hiX[k], hiY[k], hiZ[k]}; }
    float maxRadius2Bound(int k) const {
      return std::bit_cast<float>((uint32_t(maxRadius2Exponent[k]) + 1) << 23);  // 255: infinity
    }
  };
  static_assert(sizeof(Wide) == 128);
  // Whether a disc centre c in the box [lo, hi] may pass inFootprint.contains(c - x): the range
  // of (c - x)·w over the box, for each of the test's three directions w, meets the test's
  // interval. Built from the corners' offsets lo - x and hi - x, which bound every centre's
  // c - x as contains() computes it (rounding is monotonic; near x the subtractions are
  // exact), with a margin far above the rounding of the sums.
  static bool mayHoldCentreIn(const Vec3& lo, const Vec3& hi, const Vec3& x,
                              const PixelFootprint::Test& t) {
    const Vec3 below = lo - x, above = hi - x;
    const auto meets = [&](const Vec3& w, float limit) {
      float low = 0.0f, high = 0.0f, size = limit;
      for (int a = 0; a < 3; ++a) {
        const float p = below[a] * w[a], q = above[a] * w[a];
        low += std::min(p, q);
        high += std::max(p, q);
        size += std::max(std::fabs(p), std::fabs(q));
      }
      const float margin = 1e-4f * size;
      return low <= limit + margin && high >= -limit - margin;
    };
    return meets(t.normal, t.slab) && meets(t.dualA, t.limitA) && meets(t.dualB, t.limitB);
  }
  class Builder;
  static Wide emptyWide();
  static void setEntry(Wide& w, int k, const Node& n, uint32_t child);
  // Wide node for binary node `binary` (interior) and the subtrees below it; returns its index.
  uint32_t widen(const std::vector<Node>& nodes, uint32_t binary);
  // Depth first over the entries `enters` accepts (a lane mask for a Wide node's four),
  // calling atSlot(slot) for their leaves' slots.
  template <class Enters, class AtSlot>
  void walk(Enters&& enters, AtSlot&& atSlot) const;

  std::vector<Wide> wide_;
  std::vector<Disc> discs_;  // per slot
};

template <class Enters, class AtSlot>
void PhotonDiscs::walk(Enters&& enters, AtSlot&& atSlot) const {
  if (wide_.empty()) return;
  // Entries to visit, the next on top: a leaf's first slot and count, or a Wide node (count 0).
  // A node takes one entry and adds at most four, at most 15 levels deep (the binary tree stops
  // at depth 30): 46 entries at most.
  struct Item {
    uint32_t index;
    uint32_t count;
  };
  Item stack[4 * 16];
  int top = 0;
  stack[top++] = {0, 0};
  while (top > 0) {
    const Item item = stack[--top];
    if (item.count > 0) {
      for (uint32_t s = item.index; s < item.index + item.count; ++s) atSlot(s);
      continue;
    }
    const Wide& w = wide_[item.index];
    // The entries in reverse, so that the first is taken next.
    for (uint32_t m = enters(w); m != 0;) {
      const int k = 31 - __builtin_clz(m);
      m &= ~(1u << k);
      stack[top++] = {w.child[k], w.count[k]};
    }
  }
}

template <class Visit>
void PhotonDiscs::covering(const Vec3& x, Visit&& visit) const {
  using simd::Float4;
  const Float4 px = simd::broadcast<Float4>(x.x), py = simd::broadcast<Float4>(x.y),
               pz = simd::broadcast<Float4>(x.z);
  walk(
      [&](const Wide& w) {
        return simd::laneMask(
            (px >= simd::load<Float4>(w.loX)) & (py >= simd::load<Float4>(w.loY)) &
            (pz >= simd::load<Float4>(w.loZ)) & (px <= simd::load<Float4>(w.hiX)) &
            (py <= simd::load<Float4>(w.hiY)) & (pz <= simd::load<Float4>(w.hiZ)));
      },
      [&](uint32_t s) {
        const Disc& disc = discs_[s];
        const Vec3 d = x - disc.position;
        const float d2 = glm::dot(d, d);
        if (d2 < disc.radius2) visit(disc, d2, disc.radius2);
      });
}

template <class Visit>
void PhotonDiscs::reaching(const Vec3& x, float reach, float max2, float narrow2,
                           const PixelFootprint::Test& inFootprint, Visit&& visit) const {
  using simd::Float4;
  using simd::Int4;
  const Float4 px = simd::broadcast<Float4>(x.x), py = simd::broadcast<Float4>(x.y),
               pz = simd::broadcast<Float4>(x.z), r = simd::broadcast<Float4>(reach),
               most2 = simd::broadcast<Float4>(max2);
  walk(
      [&](const Wide& w) {
        const Int4 minBits = {w.minRadius2Bits[0], w.minRadius2Bits[1], w.minRadius2Bits[2],
                              w.minRadius2Bits[3]};
        const Float4 min2 = reinterpret_cast<Float4>(minBits << 16);
        uint32_t mask = simd::laneMask(
            (min2 <= most2) & (px >= simd::load<Float4>(w.loX) - r) &
            (py >= simd::load<Float4>(w.loY) - r) & (pz >= simd::load<Float4>(w.loZ) - r) &
            (px <= simd::load<Float4>(w.hiX) + r) & (py <= simd::load<Float4>(w.hiY) + r) &
            (pz <= simd::load<Float4>(w.hiZ) + r));
        // Entries holding only narrow photons: only if a centre may lie in the footprint.
        for (uint32_t m = mask; m != 0; m &= m - 1) {
          const int k = __builtin_ctz(m);
          if (!(w.maxRadius2Bound(k) > narrow2) &&
              !mayHoldCentreIn(w.lo(k), w.hi(k), x, inFootprint)) {
            mask &= ~(1u << k);
          }
        }
        return mask;
      },
      [&](uint32_t s) {
        const Disc& disc = discs_[s];
        if (disc.radius2 > max2) return;
        const Vec3 d = x - disc.position;
        if (disc.radius2 <= narrow2 && !inFootprint.contains(-d)) return;
        const float d2 = glm::dot(d, d), within = std::sqrt(disc.radius2) + reach;
        if (d2 < within * within) visit(disc, d2, disc.radius2);
      });
}

}  // namespace prism
