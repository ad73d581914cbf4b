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
    float minRadius2() const { return std::bit_cast<float>(uint32_t(minRadius2Bits) << 16); }
    float maxRadius2Bound() const {
      return std::bit_cast<float>((uint32_t(maxRadius2Exponent) + 1) << 23);  // 255: infinity
    }
    // Whether a disc centre c in the node's box may pass inFootprint.contains(c - x): the range
    // of (c - x)·w over the box, for each of the test's three directions w, meets the test's
    // interval. Built from the corners' offsets lo - x and hi - x, which bound every centre's
    // c - x as contains() computes it (rounding is monotonic; near x the subtractions are
    // exact), with a margin far above the rounding of the sums.
    bool mayHoldCentreIn(const Vec3& x, const PixelFootprint::Test& t) const {
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
  };
  static_assert(sizeof(Node) == 32);
  class Builder;
  // Depth first over the nodes `enters` accepts, calling atSlot(slot) for their leaves' slots.
  template <class Enters, class AtSlot>
  void walk(Enters&& enters, AtSlot&& atSlot) const;

  std::vector<Node> nodes_;
  std::vector<Disc> discs_;  // per slot
};

template <class Enters, class AtSlot>
void PhotonDiscs::walk(Enters&& enters, AtSlot&& atSlot) const {
  if (nodes_.empty()) return;
  uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (!enters(n)) continue;
    if (n.count > 0) {
      for (uint32_t s = n.first; s < n.first + n.count; ++s) atSlot(s);
    } else {
      const uint32_t self = static_cast<uint32_t>(&n - nodes_.data());
      stack[top++] = n.first;
      stack[top++] = self + 1;
    }
  }
}

template <class Visit>
void PhotonDiscs::covering(const Vec3& x, Visit&& visit) const {
  walk(
      [&](const Node& n) {
        return x.x >= n.lo.x && x.y >= n.lo.y && x.z >= n.lo.z && x.x <= n.hi.x && x.y <= n.hi.y &&
               x.z <= n.hi.z;
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
  walk(
      [&](const Node& n) {
        return n.minRadius2() <= max2 && x.x >= n.lo.x - reach && x.y >= n.lo.y - reach &&
               x.z >= n.lo.z - reach && x.x <= n.hi.x + reach && x.y <= n.hi.y + reach &&
               x.z <= n.hi.z + reach &&
               (n.maxRadius2Bound() > narrow2 || n.mayHoldCentreIn(x, inFootprint));
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
