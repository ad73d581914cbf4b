#include "caustics/PhotonMap.h"

#include <nanoflann.hpp>

namespace prism {
namespace {

// nanoflann's view of the photons' positions.
struct PhotonCloud {
  const std::vector<Vec3>* positions;
  size_t kdtree_get_point_count() const { return positions->size(); }
  float kdtree_get_pt(size_t i, size_t dim) const { return (*positions)[i][dim]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;  // let nanoflann compute it
  }
};

using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, PhotonCloud>,
                                                   PhotonCloud, 3, uint32_t>;

// The result sets below are handed leaf positions (the tree indexes its leaf-order copy of the
// positions) and report photon indices.

// The k nearest within a radius: like nanoflann's KNNResultSet, but the search never looks past
// maxRadius², so sparse regions cost no more than dense ones.
class BoundedNearest {
 public:
  BoundedNearest(size_t k, float maxRadius2, const uint32_t* photonAt,
                 std::vector<PhotonNeighbour>& out)
      : k_(k), maxRadius2_(maxRadius2), photonAt_(photonAt), out_(out) {
    out_.clear();
  }
  size_t size() const { return out_.size(); }
  bool full() const { return out_.size() == k_; }
  float worstDist() const { return full() ? out_.back().distance2 : maxRadius2_; }
  bool addPoint(float distance2, uint32_t index) {
    if (!(distance2 < worstDist())) return true;
    if (full()) out_.pop_back();
    auto at = out_.end();
    while (at != out_.begin() && (at - 1)->distance2 > distance2) --at;
    out_.insert(at, {photonAt_[index], distance2});
    return true;
  }

 private:
  size_t k_;
  float maxRadius2_;
  const uint32_t* photonAt_;
  std::vector<PhotonNeighbour>& out_;
};

class WithinRadius {
 public:
  WithinRadius(float radius2, const uint32_t* photonAt, std::vector<PhotonNeighbour>& out)
      : radius2_(radius2), photonAt_(photonAt), out_(out) {
    out_.clear();
  }
  size_t size() const { return out_.size(); }
  bool full() const { return true; }
  float worstDist() const { return radius2_; }
  bool addPoint(float distance2, uint32_t index) {
    if (distance2 < radius2_) out_.push_back({photonAt_[index], distance2});
    return true;
  }

 private:
  float radius2_;
  const uint32_t* photonAt_;
  std::vector<PhotonNeighbour>& out_;
};

// Only the squared distances within a radius, for a selection by rank.
class DistancesWithin {
 public:
  DistancesWithin(float radius2, std::vector<float>& out) : radius2_(radius2), out_(out) {
    out_.clear();
  }
  size_t size() const { return out_.size(); }
  bool full() const { return true; }
  float worstDist() const { return radius2_; }
  bool addPoint(float distance2, uint32_t) {
    if (distance2 < radius2_) out_.push_back(distance2);
    return true;
  }

 private:
  float radius2_;
  std::vector<float>& out_;
};

// nanoflann keeps the points' indices permuted into leaf order once the tree is built (a public
// member, named vAcc_ from nanoflann 1.5 on).
auto& leafOrder(KdTree& tree) {
#if NANOFLANN_VERSION >= 0x150
  return tree.vAcc_;
#else
  return tree.vAcc;
#endif
}

}  // namespace

// The tree walks leaves in memory order: once built over the positions, they are put in leaf
// order and the tree's permutation becomes the identity (the same nodes, the same points in the
// same order, the same float distances), so a search reads each leaf's points one after another
// instead of one cache miss each; photonAt maps a leaf position back to its photon.
struct PhotonMap::Index {
  explicit Index(const std::vector<Photon>& photons)
      : positions(positionsOf(photons)),
        cloud{&positions},
        tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(kLeafSize)) {
    auto& order = leafOrder(tree);
    photonAt.assign(order.begin(), order.end());
    for (size_t j = 0; j < order.size(); ++j) {
      positions[j] = photons[photonAt[j]].position;
      order[j] = static_cast<uint32_t>(j);
    }
  }
  static std::vector<Vec3> positionsOf(const std::vector<Photon>& photons) {
    std::vector<Vec3> out(photons.size());
    for (size_t i = 0; i < photons.size(); ++i) out[i] = photons[i].position;
    return out;
  }
  static constexpr size_t kLeafSize = 12;
  std::vector<Vec3> positions;     // in leaf order once the tree is built
  std::vector<uint32_t> photonAt;  // the photon at each leaf position
  PhotonCloud cloud;
  KdTree tree;
};

PhotonMap::PhotonMap(std::vector<Photon> photons) : photons_(std::move(photons)) {
  if (!photons_.empty()) index_ = std::make_unique<Index>(photons_);
}

PhotonMap::~PhotonMap() = default;

size_t PhotonMap::bytes() const {
  size_t total = photons_.capacity() * sizeof(Photon);
  if (index_) {
    total += index_->tree.usedMemory(index_->tree) + index_->positions.capacity() * sizeof(Vec3) +
             index_->photonAt.capacity() * sizeof(uint32_t);
  }
  return total;
}

float PhotonMap::nearest(const Vec3& p, int k, float maxRadius2,
                         std::vector<PhotonNeighbour>& out) const {
  BoundedNearest result(static_cast<size_t>(k), maxRadius2,
                        index_ ? index_->photonAt.data() : nullptr, out);
  if (index_) index_->tree.findNeighbors(result, &p.x, nanoflann::SearchParams());
  return result.full() ? out.back().distance2 : maxRadius2;
}

const std::vector<uint32_t>& PhotonMap::spatialOrder() const {
  static const std::vector<uint32_t> none;
  return index_ ? index_->photonAt : none;
}

void PhotonMap::within(const Vec3& p, float radius2, std::vector<PhotonNeighbour>& out) const {
  WithinRadius result(radius2, index_ ? index_->photonAt.data() : nullptr, out);
  if (index_) index_->tree.findNeighbors(result, &p.x, nanoflann::SearchParams());
}

void PhotonMap::distancesWithin(const Vec3& p, float radius2, std::vector<float>& out) const {
  DistancesWithin result(radius2, out);
  if (index_) index_->tree.findNeighbors(result, &p.x, nanoflann::SearchParams());
}

}  // namespace prism
