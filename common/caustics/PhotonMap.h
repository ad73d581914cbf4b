// The stored caustic photons of one pass, indexed by a kd-tree (nanoflann, a well-kept
// header-only k-NN library; see docs/dependencies.md) for nearest-neighbour and fixed-radius
// queries. Every rank builds it from the same photons in the same order, so queries give
// identical answers everywhere.
#pragma once

#include <memory>
#include <vector>

#include "caustics/Photon.h"

namespace prism {

struct PhotonNeighbour {
  uint32_t index;
  float distance2;
};

class PhotonMap {
 public:
  explicit PhotonMap(std::vector<Photon> photons);
  ~PhotonMap();
  PhotonMap(const PhotonMap&) = delete;
  PhotonMap& operator=(const PhotonMap&) = delete;

  const std::vector<Photon>& photons() const { return photons_; }
  size_t size() const { return photons_.size(); }
  // Every photon's index once, neighbours in space next to each other (the tree's leaf order):
  // queries made in this order find the tree's nodes and photons in the cache.
  const std::vector<uint32_t>& spatialOrder() const;
  // Photons plus the kd-tree, as resident in memory.
  size_t bytes() const;

  // The k nearest photons within maxRadius² of p, nearest first, into out. Returns the squared
  // gather radius: the k-th distance when k were found, maxRadius² otherwise.
  float nearest(const Vec3& p, int k, float maxRadius2, std::vector<PhotonNeighbour>& out) const;
  // Every photon within radius² of p, in tree order, into out.
  void within(const Vec3& p, float radius2, std::vector<PhotonNeighbour>& out) const;
  // The squared distances (as nearest() compares them) of every photon within radius² of p.
  void distancesWithin(const Vec3& p, float radius2, std::vector<float>& out) const;

 private:
  struct Index;
  std::vector<Photon> photons_;
  std::unique_ptr<Index> index_;
};

}  // namespace prism
