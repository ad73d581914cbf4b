#include "caustics/PhotonMap.h"

#include <nanoflann.hpp>

namespace prism {
namespace {

// nanoflann's view of the photon array.
struct PhotonCloud {
  const std::vector<Photon>* photons;
  size_t kdtree_get_point_count() const { return photons->size(); }
  float kdtree_get_pt(size_t i, size_t dim) const { return (*photons)[i].position[dim]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;  // let nanoflann compute it
  }
};

using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, PhotonCloud>,
                                                   PhotonCloud, 3, uint32_t>;

// The k nearest within a radius: like nanoflann's KNNResultSet, but the search never looks past
// maxRadius², so sparse regions cost no more than dense ones.
class BoundedNearest {
 public:
  BoundedNearest(size_t k, float maxRadius2, std::vector<PhotonNeighbour>& out)
      : k_(k), maxRadius2_(maxRadius2), out_(out) {
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
    out_.insert(at, {index, distance2});
    return true;
  }

 private:
  size_t k_;
  float maxRadius2_;
  std::vector<PhotonNeighbour>& out_;
};

class WithinRadius {
 public:
  WithinRadius(float radius2, std::vector<PhotonNeighbour>& out) : radius2_(radius2), out_(out) {
    out_.clear();
  }
  size_t size() const { return out_.size(); }
  bool full() const { return true; }
  float worstDist() const { return radius2_; }
  bool addPoint(float distance2, uint32_t index) {
    if (distance2 < radius2_) out_.push_back({index, distance2});
    return true;
  }

 private:
  float radius2_;
  std::vector<PhotonNeighbour>& out_;
};

// nanoflann keeps the photons' indices permuted into leaf order once the tree is built (a public
// member, named vAcc_ from nanoflann 1.5 on).
const auto& leafOrder(const KdTree& tree) {
#if NANOFLANN_VERSION >= 0x150
  return tree.vAcc_;
#else
  return tree.vAcc;
#endif
}

}  // namespace

struct PhotonMap::Index {
  explicit Index(const std::vector<Photon>& photons)
      : cloud{&photons}, tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(kLeafSize)) {}
  static constexpr size_t kLeafSize = 12;
  PhotonCloud cloud;
  KdTree tree;
};

PhotonMap::PhotonMap(std::vector<Photon> photons) : photons_(std::move(photons)) {
  if (!photons_.empty()) index_ = std::make_unique<Index>(photons_);
}

PhotonMap::~PhotonMap() = default;

size_t PhotonMap::bytes() const {
  size_t total = photons_.capacity() * sizeof(Photon);
  if (index_) total += index_->tree.usedMemory(index_->tree);
  return total;
}

float PhotonMap::nearest(const Vec3& p, int k, float maxRadius2,
                         std::vector<PhotonNeighbour>& out) const {
  BoundedNearest result(static_cast<size_t>(k), maxRadius2, out);
  if (index_) index_->tree.findNeighbors(result, &p.x, nanoflann::SearchParams());
  return result.full() ? out.back().distance2 : maxRadius2;
}

std::vector<uint32_t> PhotonMap::spatialOrder() const {
  if (!index_) return {};
  const auto& order = leafOrder(index_->tree);
  return std::vector<uint32_t>(order.begin(), order.end());
}

void PhotonMap::within(const Vec3& p, float radius2, std::vector<PhotonNeighbour>& out) const {
  WithinRadius result(radius2, out);
  if (index_) index_->tree.findNeighbors(result, &p.x, nanoflann::SearchParams());
}

}  // namespace prism
