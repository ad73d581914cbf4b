#include "caustics/GatherRadius.h"
#include "caustics/AutomaticGather.h"
#include "caustics/PhotonGather.h"
#include "caustics/PhotonRadii.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "tests/common/caustics/BallOverFloorScene.h"

namespace prism {
namespace {

TEST(GatherRadius, Automatic) {
  SceneDescription d = test::ballOverFloorScene(1.0f);
  d.spheres.push_back({{5, 1, 0}, 2.5f, 0, {}});
  EXPECT_FLOAT_EQ(automaticMaxRadius(Scene(d)), 0.25f);  // a tenth of the largest caster
  // Only a casting plane: a hundredth of the bounded objects' extent (the diffuse sphere's box,
  // 2 × 2 × 2: diagonal 2√3).
  SceneDescription planes;
  MaterialDesc mirror;
  mirror.reflectance = Color(1.0f);
  planes.materials = {mirror, MaterialDesc{}};
  planes.planes.push_back({{0, 0, 0}, {0, 1, 0}, 0, {}});
  planes.spheres.push_back({{0, 3, 0}, 1.0f, 1, {}});
  EXPECT_NEAR(automaticMaxRadius(Scene(planes)), 0.02f * std::sqrt(3.0f), 1e-6f);
}

// Per-photon radii: the distance to the k-th nearest photon, itself counted first. Photons on a
// line with unit spacing: the 3rd nearest of an interior photon is 1 away, of an end photon 2.
TEST(GatherRadius, PhotonRadiiAreTheKthNeighbourDistanceCapped) {
  std::vector<Photon> line(300);
  for (size_t i = 0; i < line.size(); ++i) line[i].position = {static_cast<float>(i), 0, 0};
  const PhotonMap map(std::move(line));
  const std::vector<float> radii = photonRadii(map, 3, 10.0f, false, 2);
  ASSERT_EQ(radii.size(), 300u);
  EXPECT_FLOAT_EQ(radii[0], 2.0f);
  EXPECT_FLOAT_EQ(radii[150], 1.0f);
  EXPECT_FLOAT_EQ(radii[299], 2.0f);
  EXPECT_FLOAT_EQ(photonRadii(map, 3, 1.5f, false, 2)[0], 1.5f);  // capped
}

// Every radius equals a brute-force k-th nearest distance (squared as the kd-tree squares it,
// capped at maxRadius), bit for bit: dense clusters, a sparse field where fewer than k photons
// lie within maxRadius, a line, and a pile of identical photons, for several k and thread counts.
void expectRadiiEqualBruteForce(const Vec3& offset) {
  std::mt19937 rng(7);
  std::normal_distribution<float> tight(0.0f, 0.002f);
  std::uniform_real_distribution<float> wide(-3.0f, 3.0f);
  std::vector<Photon> photons;
  for (int cluster = 0; cluster < 6; ++cluster) {
    const Vec3 centre = offset + Vec3(wide(rng), 0.0f, wide(rng));
    for (int i = 0; i < 400; ++i) photons.push_back({centre + Vec3(tight(rng), 0, tight(rng))});
  }
  for (int i = 0; i < 300; ++i) {
    photons.push_back({offset + Vec3(wide(rng), wide(rng) * 0.01f, wide(rng))});
  }
  for (int i = 0; i < 200; ++i) photons.push_back({offset + Vec3(5.0f + 1e-4f * i, 1.0f, -2.0f)});
  for (int i = 0; i < 40; ++i) photons.push_back({offset + Vec3(-4.0f, 0.5f, 4.0f)});
  std::vector<Vec3> positions;
  for (const Photon& p : photons) positions.push_back(p.position);
  const PhotonMap map(std::move(photons));
  const float maxRadius = 0.05f, maxRadius2 = maxRadius * maxRadius;
  for (int k : {1, 7, 50}) {
    std::vector<float> expected(positions.size());
    for (size_t i = 0; i < positions.size(); ++i) {
      std::vector<float> within;
      for (const Vec3& q : positions) {
        float d2 = 0.0f;
        for (int a = 0; a < 3; ++a) {
          const float diff = positions[i][a] - q[a];
          d2 += diff * diff;
        }
        if (d2 < maxRadius2) within.push_back(d2);
      }
      if (within.size() < static_cast<size_t>(k)) {
        expected[i] = maxRadius;
        continue;
      }
      std::nth_element(within.begin(), within.begin() + (k - 1), within.end());
      expected[i] = std::sqrt(within[k - 1]);
    }
    for (int threads : {1, 2}) {
      const std::vector<float> radii = photonRadii(map, k, maxRadius, false, threads);
      size_t capped = 0, wrong = 0;
      for (size_t i = 0; i < radii.size(); ++i) {
        capped += expected[i] == maxRadius;
        wrong += radii[i] != expected[i];
      }
      EXPECT_EQ(wrong, 0u) << "k " << k << ", threads " << threads;
      if (k > 1) {
        EXPECT_GT(capped, 0u) << "k " << k;  // the sparse field is capped
      }
      EXPECT_LT(capped, radii.size()) << "k " << k;
    }
  }
}

TEST(GatherRadius, PhotonRadiiEqualBruteForceKthDistancesExactly) {
  // At the origin, and far from it, where a coordinate keeps fewer digits of the spacing.
  for (const Vec3 offset : {Vec3(0.0f), Vec3(2000.0f, -30.0f, 700.0f)}) {
    SCOPED_TRACE("offset " + std::to_string(offset.x));
    expectRadiiEqualBruteForce(offset);
  }
}

// With the automatic k, every radius is the ladder's choice over the tree's own k nearest
// (PhotonMap::nearest), bit for bit: on a caustic-like field (a bright fold over a dim disc, a
// sparse halo, a pile of identical photons) for k up to 400 and both thread counts.
TEST(GatherRadius, AutomaticPhotonRadiiEqualTheTreesNearestExactly) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<Photon> photons;
  for (int i = 0; i < 6000; ++i) {  // a dim disc of radius 1
    const float r = std::sqrt(unit(rng)), a = 6.2831853f * unit(rng);
    photons.push_back({Vec3(r * std::cos(a), 0.0f, r * std::sin(a))});
  }
  for (int i = 0; i < 3000; ++i) {  // a bright fold along a circle of radius 0.6
    const float r = 0.6f + 0.004f * unit(rng), a = 6.2831853f * unit(rng);
    photons.push_back({Vec3(r * std::cos(a), 0.0f, r * std::sin(a))});
  }
  for (int i = 0; i < 300; ++i) {  // a sparse halo, some beyond any k within maxRadius
    photons.push_back({Vec3(4.0f * unit(rng) - 2.0f, 0.3f * unit(rng), 4.0f * unit(rng) - 2.0f)});
  }
  for (int i = 0; i < 500; ++i) photons.push_back({Vec3(0.25f, 0.0f, -0.25f)});
  const PhotonMap map(std::move(photons));
  const float maxRadius = 0.15f, maxRadius2 = maxRadius * maxRadius;
  for (int k : {8, 100, 400}) {
    std::vector<float> expected(map.size());
    std::vector<PhotonNeighbour> nearest;
    for (size_t i = 0; i < map.size(); ++i) {
      map.nearest(map.photons()[i].position, k, maxRadius2, nearest);
      expected[i] = std::sqrt(automaticGatherRadius2(nearest, k, maxRadius2));
    }
    for (int threads : {1, 2}) {
      const std::vector<float> radii = photonRadii(map, k, maxRadius, true, threads);
      size_t wrong = 0, capped = 0;
      for (size_t i = 0; i < radii.size(); ++i) {
        wrong += radii[i] != expected[i];
        capped += expected[i] == maxRadius;
      }
      EXPECT_EQ(wrong, 0u) << "k " << k << ", threads " << threads;
      EXPECT_GT(capped, 0u) << "k " << k;  // the halo reaches the cap
    }
    // Found in shares of whole chunks (as the ranks of a run find them) and put together: the
    // same radii.
    std::vector<float> together(map.size(), -1.0f);
    const size_t cuts[] = {0, 7 * kPhotonRadiiChunk, 40 * kPhotonRadiiChunk, map.size()};
    for (size_t s = 0; s + 1 < std::size(cuts); ++s) {
      const std::vector<float> share =
          photonRadiiShare(map, k, maxRadius, true, cuts[s], cuts[s + 1] - cuts[s], 2);
      ASSERT_EQ(share.size(), cuts[s + 1] - cuts[s]);
      placePhotonRadii(map, cuts[s], share, together);
    }
    EXPECT_EQ(together, expected) << "k " << k;
  }
  // A share must start at a chunk and end inside the map.
  EXPECT_THROW(photonRadiiShare(map, 8, maxRadius, true, kPhotonRadiiChunk + 1, 10),
               std::invalid_argument);
  EXPECT_THROW(photonRadiiShare(map, 8, maxRadius, true, 0, map.size() + 1), std::invalid_argument);
}

// The progressive schedule: r²(i) = r²(i−1)·(i − 1 + α)/i, applied to the one fixed radius when
// the scene sets it, else to the per-photon radii through their common scale (1 at pass 1).
TEST(GatherRadius, ProgressiveScheduleShrinksByTheAlphaRule) {
  CausticSettings c;
  c.gather = 50;
  c.alpha = 0.5f;
  PhotonGatherSettings g = progressiveGather(c, 0.2f, 1, {});
  EXPECT_FALSE(g.fixedRadius);
  EXPECT_EQ(g.k, 50);
  EXPECT_FLOAT_EQ(g.radius, 0.2f);
  EXPECT_FLOAT_EQ(g.radiusScale, 1.0f);
  g = progressiveGather(c, 0.2f, 2, g);
  EXPECT_FLOAT_EQ(g.radiusScale * g.radiusScale, 1.5f / 2.0f);
  g = progressiveGather(c, 0.2f, 3, g);
  EXPECT_FLOAT_EQ(g.radiusScale * g.radiusScale, (1.5f / 2.0f) * (2.5f / 3.0f));
  EXPECT_FLOAT_EQ(g.radius, 0.2f);  // the cap is scaled with the radii, not here

  c.radius = 0.1f;
  g = progressiveGather(c, 0.2f, 1, {});
  EXPECT_TRUE(g.fixedRadius);
  EXPECT_FLOAT_EQ(g.radius, 0.1f);
  g = progressiveGather(c, 0.2f, 2, g);
  EXPECT_FLOAT_EQ(g.radius * g.radius, 0.01f * 0.75f);
}

}  // namespace
}  // namespace prism
