#include "caustics/PhotonMap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace prism {
namespace {

std::vector<Photon> randomPhotons(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<Photon> photons(n);
  for (Photon& p : photons) {
    p.position = {u(rng), u(rng), 0.25f * u(rng)};  // a thick slab, like photons on a surface
    p.power = Color(1.0f);
  }
  return photons;
}

// Squared distance summed in the same order as the kd-tree's metric.
float distance2(const Vec3& a, const Vec3& b) {
  const Vec3 d = a - b;
  return d.x * d.x + d.y * d.y + d.z * d.z;
}

std::vector<PhotonNeighbour> bruteForceSorted(const std::vector<Photon>& photons, const Vec3& q) {
  std::vector<PhotonNeighbour> all;
  for (uint32_t i = 0; i < photons.size(); ++i)
    all.push_back({i, distance2(photons[i].position, q)});
  std::sort(all.begin(), all.end(),
            [](const auto& a, const auto& b) { return a.distance2 < b.distance2; });
  return all;
}

class PhotonMapTest : public testing::Test {
 protected:
  PhotonMapTest() : photons_(randomPhotons(3000, 5)), map_(photons_) {}
  std::vector<Vec3> queries() const {
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(-1.2f, 1.2f);
    std::vector<Vec3> q;
    for (int i = 0; i < 60; ++i) q.push_back({u(rng), u(rng), 0.3f * u(rng)});
    return q;
  }
  std::vector<Photon> photons_;
  PhotonMap map_;
};

TEST_F(PhotonMapTest, KeepsThePhotonsInOrder) {
  ASSERT_EQ(map_.size(), photons_.size());
  for (size_t i = 0; i < photons_.size(); ++i) {
    EXPECT_EQ(map_.photons()[i].position, photons_[i].position);
  }
  EXPECT_GE(map_.bytes(), photons_.size() * sizeof(Photon));
}

TEST_F(PhotonMapTest, NearestReturnsExactlyTheKNearestInOrder) {
  std::vector<PhotonNeighbour> out;
  for (const Vec3& q : queries()) {
    for (int k : {1, 7, 50}) {
      const std::vector<PhotonNeighbour> expected = bruteForceSorted(photons_, q);
      const float r2 = map_.nearest(q, k, 100.0f, out);
      ASSERT_EQ(out.size(), static_cast<size_t>(k));
      for (int i = 0; i < k; ++i) {
        EXPECT_EQ(out[i].index, expected[i].index) << "k " << k << ", neighbour " << i;
        EXPECT_FLOAT_EQ(out[i].distance2, expected[i].distance2);
      }
      EXPECT_FLOAT_EQ(r2, expected[k - 1].distance2);  // the gather radius is the k-th distance
    }
  }
}

TEST_F(PhotonMapTest, NearestStopsAtTheMaximumRadius) {
  std::vector<PhotonNeighbour> out;
  const float maxRadius2 = 0.01f;  // r = 0.1: about 3000·π·0.01/(2·2·0.5) ≈ 47 photons in reach
  for (const Vec3& q : queries()) {
    const std::vector<PhotonNeighbour> expected = bruteForceSorted(photons_, q);
    const size_t inReach =
        std::count_if(expected.begin(), expected.end(),
                      [&](const PhotonNeighbour& n) { return n.distance2 < maxRadius2; });
    const int k = 200;  // more than are ever in reach
    const float r2 = map_.nearest(q, k, maxRadius2, out);
    ASSERT_EQ(out.size(), inReach);
    EXPECT_EQ(r2, maxRadius2);  // fewer than k found: the radius is the cap
    for (size_t i = 0; i < inReach; ++i) EXPECT_EQ(out[i].index, expected[i].index);
  }
}

// The order photonRadii queries in: every photon once, and neighbours close together (the
// mean distance between successive photons far below a random order's).
TEST_F(PhotonMapTest, SpatialOrderIsAPermutationThatKeepsNeighboursTogether) {
  std::vector<uint32_t> order = map_.spatialOrder();
  ASSERT_EQ(order.size(), photons_.size());
  double ordered = 0.0, stored = 0.0;
  for (size_t i = 1; i < order.size(); ++i) {
    ordered += std::sqrt(distance2(photons_[order[i]].position, photons_[order[i - 1]].position));
    stored += std::sqrt(distance2(photons_[i].position, photons_[i - 1].position));
  }
  EXPECT_LT(ordered, 0.25 * stored);
  std::sort(order.begin(), order.end());
  for (uint32_t i = 0; i < order.size(); ++i) ASSERT_EQ(order[i], i);
  EXPECT_TRUE(PhotonMap({}).spatialOrder().empty());
}

TEST_F(PhotonMapTest, WithinEqualsTheBruteForceSet) {
  std::vector<PhotonNeighbour> out;
  for (const Vec3& q : queries()) {
    for (float radius : {0.0f, 0.05f, 0.2f, 0.5f}) {
      const float r2 = radius * radius;
      map_.within(q, r2, out);
      std::vector<uint32_t> got, expected;
      for (const PhotonNeighbour& n : out) {
        got.push_back(n.index);
        EXPECT_FLOAT_EQ(n.distance2, distance2(photons_[n.index].position, q));
      }
      for (uint32_t i = 0; i < photons_.size(); ++i) {
        if (distance2(photons_[i].position, q) < r2) expected.push_back(i);
      }
      std::sort(got.begin(), got.end());
      EXPECT_EQ(got, expected) << "radius " << radius;
    }
  }
}

TEST(PhotonMap, EmptyMapAnswersNothing) {
  const PhotonMap map({});
  std::vector<PhotonNeighbour> out = {{1, 2.0f}};
  EXPECT_EQ(map.nearest(Vec3(0.0f), 5, 0.25f, out), 0.25f);
  EXPECT_TRUE(out.empty());
  out = {{1, 2.0f}};
  map.within(Vec3(0.0f), 1.0f, out);
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(map.size(), 0u);
}

// Photons stacked on one point (a perfect focus) must not break the tree.
TEST(PhotonMap, CoincidentPhotons) {
  std::vector<Photon> photons(500);
  for (Photon& p : photons) p.position = {1, 2, 3};
  const PhotonMap map(std::move(photons));
  std::vector<PhotonNeighbour> out;
  EXPECT_EQ(map.nearest({1, 2, 3}, 10, 1.0f, out), 0.0f);
  EXPECT_EQ(out.size(), 10u);
  map.within({1, 2, 3.5f}, 0.3f, out);
  EXPECT_EQ(out.size(), 500u);
}

}  // namespace
}  // namespace prism
