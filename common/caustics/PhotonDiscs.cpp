#include "caustics/PhotonDiscs.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "util/Parallel.h"
#include "util/ThreadCount.h"

namespace prism {
namespace {
constexpr uint32_t kLeafSize = 8;
static_assert(kLeafSize <= 255, "a leaf's count is a byte (Node::count)");
constexpr uint32_t kDiscBlock = 4096;  // discs filled per parallel item
}  // namespace

// Builds the tree over photons' entries in slot order. Each node splits its slots at the median
// (the lower half first), so the size of every subtree, and where its nodes go in depth-first
// order, follows from its slot count alone: subtrees below the top levels are built in parallel
// into their places, and the tree is the same for any thread count.
class PhotonDiscs::Builder {
 public:
  // What the build moves around: 24 bytes in place of a 40-byte disc.
  struct Entry {
    Vec3 position;
    float radius;  // sqrt(radius2), as the bounds use it
    float radius2;
    uint32_t photon;  // breaks ties, so the tree is the same on every rank
  };

  Builder(std::vector<Entry>& entries, std::vector<Node>& nodes)
      : entries_(entries), nodes_(nodes) {}

  static bool isLeaf(uint32_t count, int depth) { return count <= kLeafSize || depth >= 30; }

  // Nodes of a subtree over `count` slots whose root is at `depth`.
  static uint32_t nodeCount(uint32_t count, int depth) {
    if (isLeaf(count, depth)) return 1;
    return 1 + nodeCount(count / 2, depth + 1) + nodeCount(count - count / 2, depth + 1);
  }

  // Node `self` over slots [begin, end): bounds, and the split (entries reordered) unless a leaf.
  // Returns whether it is a leaf.
  bool place(uint32_t self, uint32_t begin, uint32_t end, int depth) {
    Vec3 lo(1e30f), hi(-1e30f), clo(1e30f), chi(-1e30f);
    float minRadius2 = 1e30f, maxRadius2 = 0.0f;
    for (uint32_t s = begin; s < end; ++s) {
      const Entry& e = entries_[s];
      minRadius2 = std::min(minRadius2, e.radius2);
      maxRadius2 = std::max(maxRadius2, e.radius2);
      lo = glm::min(lo, e.position - Vec3(e.radius));
      hi = glm::max(hi, e.position + Vec3(e.radius));
      clo = glm::min(clo, e.position);
      chi = glm::max(chi, e.position);
    }
    Node& node = nodes_[self];
    node.lo = lo;
    node.hi = hi;
    node.minRadius2Bits = static_cast<uint16_t>(std::bit_cast<uint32_t>(minRadius2) >> 16);
    node.maxRadius2Exponent =
        static_cast<uint8_t>((std::bit_cast<uint32_t>(maxRadius2) >> 23) & 0xffu);
    // A leaf when small, or at the depth the query stack allows (64 holds 2 per level).
    if (isLeaf(end - begin, depth)) {
      node.first = begin;
      node.count = static_cast<uint8_t>(end - begin);
      return true;
    }
    // Split at the median slot along the centres' widest axis; ties broken by photon index.
    const Vec3 extent = chi - clo;
    const int axis =
        extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(entries_.begin() + begin, entries_.begin() + mid, entries_.begin() + end,
                     [axis](const Entry& a, const Entry& b) {
                       const float ca = a.position[axis], cb = b.position[axis];
                       return ca < cb || (ca == cb && a.photon < b.photon);
                     });
    node.first = self + 1 + nodeCount(mid - begin, depth + 1);  // the second child
    node.count = 0;
    return false;
  }

  void subtree(uint32_t self, uint32_t begin, uint32_t end, int depth) {
    if (place(self, begin, end, depth)) return;
    const uint32_t mid = begin + (end - begin) / 2;
    subtree(self + 1, begin, mid, depth + 1);
    subtree(nodes_[self].first, mid, end, depth + 1);
  }

  // The top `levels` levels here, then every subtree below them on up to `threads` threads.
  void build(uint32_t count, int levels, int threads) {
    struct Pending {
      uint32_t self, begin, end;
      int depth;
    };
    // The nodes at the next depth still to place; a leaf has no children to add.
    std::vector<Pending> frontier = {{0, 0, count, 0}};
    for (int depth = 0; depth < levels; ++depth) {
      std::vector<Pending> next;
      for (const Pending& p : frontier) {
        if (place(p.self, p.begin, p.end, p.depth)) continue;
        const uint32_t mid = p.begin + (p.end - p.begin) / 2;
        next.push_back({p.self + 1, p.begin, mid, p.depth + 1});
        next.push_back({nodes_[p.self].first, mid, p.end, p.depth + 1});
      }
      frontier = std::move(next);
    }
    parallelFor(frontier.size(), threads, [&](uint64_t i) {
      const Pending& p = frontier[i];
      subtree(p.self, p.begin, p.end, p.depth);
    });
  }

 private:
  std::vector<Entry>& entries_;
  std::vector<Node>& nodes_;
};

// A Wide node whose entries all fail every test: empty boxes, no radius small enough.
PhotonDiscs::Wide PhotonDiscs::emptyWide() {
  Wide w{};
  for (int k = 0; k < 4; ++k) {
    w.loX[k] = w.loY[k] = w.loZ[k] = std::numeric_limits<float>::infinity();
    w.hiX[k] = w.hiY[k] = w.hiZ[k] = -std::numeric_limits<float>::infinity();
    w.minRadius2Bits[k] = 0x7f80;  // infinity's top bits
  }
  return w;
}

void PhotonDiscs::setEntry(Wide& w, int k, const Node& n, uint32_t child) {
  w.loX[k] = n.lo.x;
  w.loY[k] = n.lo.y;
  w.loZ[k] = n.lo.z;
  w.hiX[k] = n.hi.x;
  w.hiY[k] = n.hi.y;
  w.hiZ[k] = n.hi.z;
  w.child[k] = child;
  w.count[k] = n.count;
  w.maxRadius2Exponent[k] = n.maxRadius2Exponent;
  w.minRadius2Bits[k] = n.minRadius2Bits;
}

uint32_t PhotonDiscs::widen(const std::vector<Node>& nodes, uint32_t binary) {
  const uint32_t self = static_cast<uint32_t>(wide_.size());
  wide_.push_back(emptyWide());
  // The entries: each child, or its two children where it has them, in depth-first order.
  uint32_t entries[4];
  int count = 0;
  for (const uint32_t child : {binary + 1, nodes[binary].first}) {
    if (nodes[child].count > 0) {
      entries[count++] = child;
    } else {
      entries[count++] = child + 1;
      entries[count++] = nodes[child].first;
    }
  }
  for (int k = 0; k < count; ++k) {
    const Node& n = nodes[entries[k]];
    // wide_ grows below: the entry is written after the subtree's nodes are.
    const uint32_t child = n.count > 0 ? n.first : widen(nodes, entries[k]);
    setEntry(wide_[self], k, n, child);
  }
  return self;
}

PhotonDiscs::PhotonDiscs(const std::vector<Photon>& photons, const std::vector<float>& radii,
                         int threads) {
  const uint32_t n = static_cast<uint32_t>(photons.size());
  if (n == 0) return;
  std::vector<Builder::Entry> entries(n);
  for (uint32_t i = 0; i < n; ++i) {
    const float radius2 = radii[i] * radii[i];
    entries[i] = {photons[i].position, std::sqrt(radius2), radius2, i};
  }
  std::vector<Node> nodes(Builder::nodeCount(n, 0));
  // Enough subtrees below the top levels for every thread to take several.
  const int workers = ThreadCount::resolve(threads).value();
  int levels = 0;
  while (levels < 20 && (1 << levels) < 4 * workers) ++levels;
  Builder(entries, nodes).build(n, levels, workers);
  if (nodes[0].count > 0) {
    // One leaf: a Wide root with it as its only entry.
    wide_.push_back(emptyWide());
    setEntry(wide_[0], 0, nodes[0], nodes[0].first);
  } else {
    wide_.reserve(nodes.size() / 3 + 1);
    widen(nodes, 0);
  }
  discs_.resize(n);
  parallelFor((n + kDiscBlock - 1) / kDiscBlock, workers, [&](uint64_t block) {
    const uint32_t first = static_cast<uint32_t>(block * kDiscBlock);
    const uint32_t last = std::min<uint32_t>(n, first + kDiscBlock);
    for (uint32_t s = first; s < last; ++s) {
      const Builder::Entry& e = entries[s];
      const Photon& p = photons[e.photon];
      discs_[s] = {e.position, e.radius2, p.power, p.directionVector()};
    }
  });
}

}  // namespace prism
