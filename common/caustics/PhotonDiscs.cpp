#include "caustics/PhotonDiscs.h"

#include <algorithm>
#include <bit>
#include <numeric>

namespace prism {
namespace {
constexpr uint32_t kLeafSize = 8;
static_assert(kLeafSize <= 255, "a leaf's count is a byte (Node::count)");
}  // namespace

PhotonDiscs::PhotonDiscs(const std::vector<Photon>& photons, const std::vector<float>& radii) {
  const uint32_t n = static_cast<uint32_t>(photons.size());
  if (n == 0) return;
  index_.resize(n);
  std::iota(index_.begin(), index_.end(), 0u);
  discs_.resize(n);
  for (uint32_t i = 0; i < n; ++i) {
    const Photon& p = photons[i];
    discs_[i] = {p.position, radii[i] * radii[i], p.power, p.directionVector()};
  }
  nodes_.reserve(2 * (n / kLeafSize + 1));
  build(0, n, 0);
  index_ = {};
}

uint32_t PhotonDiscs::build(uint32_t begin, uint32_t end, int depth) {
  const uint32_t self = static_cast<uint32_t>(nodes_.size());
  nodes_.push_back({});
  Vec3 lo(1e30f), hi(-1e30f), clo(1e30f), chi(-1e30f);
  float minRadius2 = 1e30f, maxRadius2 = 0.0f;
  for (uint32_t s = begin; s < end; ++s) {
    const Vec3& centre = discs_[s].position;
    minRadius2 = std::min(minRadius2, discs_[s].radius2);
    maxRadius2 = std::max(maxRadius2, discs_[s].radius2);
    const float r = std::sqrt(discs_[s].radius2);
    lo = glm::min(lo, centre - Vec3(r));
    hi = glm::max(hi, centre + Vec3(r));
    clo = glm::min(clo, centre);
    chi = glm::max(chi, centre);
  }
  nodes_[self].lo = lo;
  nodes_[self].hi = hi;
  nodes_[self].minRadius2Bits = static_cast<uint16_t>(std::bit_cast<uint32_t>(minRadius2) >> 16);
  nodes_[self].maxRadius2Exponent =
      static_cast<uint8_t>((std::bit_cast<uint32_t>(maxRadius2) >> 23) & 0xffu);
  // A leaf when small, or at the depth the query stack allows (64 holds 2 per level).
  if (end - begin <= kLeafSize || depth >= 30) {
    nodes_[self].first = begin;
    nodes_[self].count = static_cast<uint8_t>(end - begin);
    return self;
  }
  // Split at the median slot along the centres' widest axis; ties broken by photon index so the
  // tree is the same on every rank.
  const Vec3 extent = chi - clo;
  const int axis =
      extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  const uint32_t mid = begin + (end - begin) / 2;
  std::vector<uint32_t> slots(end - begin);
  std::iota(slots.begin(), slots.end(), begin);
  std::nth_element(slots.begin(), slots.begin() + (mid - begin), slots.end(),
                   [&](uint32_t a, uint32_t b) {
                     const float ca = discs_[a].position[axis], cb = discs_[b].position[axis];
                     return ca < cb || (ca == cb && index_[a] < index_[b]);
                   });
  std::vector<uint32_t> index(slots.size());
  std::vector<Disc> discs(slots.size());
  for (size_t i = 0; i < slots.size(); ++i) {
    index[i] = index_[slots[i]];
    discs[i] = discs_[slots[i]];
  }
  std::copy(index.begin(), index.end(), index_.begin() + begin);
  std::copy(discs.begin(), discs.end(), discs_.begin() + begin);
  build(begin, mid, depth + 1);
  const uint32_t second = build(mid, end, depth + 1);
  nodes_[self].first = second;
  nodes_[self].count = 0;
  return self;
}

}  // namespace prism
