#include "caustics/PhotonDiscs.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace prism {
namespace {

// reaching() with narrow2 skips the narrow photons whose centre lies outside the footprint, in
// whole subtrees where it can: it must visit exactly the photons the full walk visits less
// those, in the same order. Photons on a slightly rough plane, with radii from far narrower to
// far wider than the footprints (all narrow in a band, as in a focus); footprints square and as
// slivers (grazing views), turned every way in the plane, and one degenerate (no area: every narrow
// photon counts nothing).
TEST(PhotonDiscs, ReachingSkipsExactlyTheNarrowPhotonsOutsideTheFootprint) {
  struct Visited {
    Vec3 position;
    float radius2;
    bool operator==(const Visited&) const = default;
  };
  std::mt19937 rng(23);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  // At the origin, and far from it (where coordinates carry fewer digits of a footprint).
  for (const Vec3 offset : {Vec3(0.0f), Vec3(300.0f, 20.0f, -500.0f)}) {
    std::vector<Photon> photons(20000);
    std::vector<float> radii(photons.size());
    for (size_t i = 0; i < photons.size(); ++i) {
      const Vec3 p(2.0f * u(rng) - 1.0f, 1e-4f * u(rng), 2.0f * u(rng) - 1.0f);
      photons[i].position = offset + p;
      // Narrow in a band (a focus: whole subtrees of narrow photons), mixed elsewhere.
      radii[i] =
          std::fabs(p.x) < 0.4f ? 0.001f + 0.002f * u(rng) : 0.002f * std::pow(30.0f, u(rng));
    }
    const PhotonDiscs discs(photons, radii);
    size_t skipped = 0, counted = 0;
    for (int q = 0; q < 400; ++q) {
      const Vec3 x = offset + Vec3(1.6f * u(rng) - 0.8f, 0.0f, 1.6f * u(rng) - 0.8f);
      const float angle = 6.2831853f * u(rng), side = 0.004f + 0.02f * u(rng);
      const float sliver = q % 3 == 0 ? 1.0f : 10.0f + 10.0f * u(rng);
      PixelFootprint f{true, side * Vec3(std::cos(angle), 0.0f, std::sin(angle)),
                       side * sliver * Vec3(-std::sin(angle), 0.0f, std::cos(angle))};
      if (q == 7) f.b = 2.0f * f.a;  // degenerate: no area
      const PixelFootprint::Test test = f.test(Vec3(0.0f, 1.0f, 0.0f));
      const float reach = f.reach(), narrow2 = f.area() / 3.14159265f;
      const float max2 = std::max(narrow2, reach * reach);
      std::vector<Visited> expected, got;
      discs.reaching(x, reach, max2, -1.0f, test,
                     [&](const PhotonDiscs::Disc& d, float, float radius2) {
                       if (radius2 > narrow2 || test.contains(d.position - x)) {
                         expected.push_back({d.position, radius2});
                       } else {
                         ++skipped;
                       }
                     });
      discs.reaching(x, reach, max2, narrow2, test,
                     [&](const PhotonDiscs::Disc& d, float, float radius2) {
                       got.push_back({d.position, radius2});
                     });
      ASSERT_EQ(got, expected) << "query " << q << ", offset " << offset.x;
      counted += got.size();
    }
    EXPECT_GT(counted, 1000u);
    EXPECT_GT(skipped, 10000u);  // the narrow photons in reach but outside the footprint
  }
}

// covering() visits exactly the discs that cover x (against a brute-force test of every disc),
// and the tree, with the order it visits them in, is the same for any thread count: the
// subtrees below the top levels are built in parallel. Clusters, a sparse field and a pile of
// identical photons (ties broken by photon index).
TEST(PhotonDiscs, CoveringFindsEveryCoveringDiscInOneOrderForAnyThreadCount) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Photon> photons;
  std::vector<float> radii;
  for (int i = 0; i < 30000; ++i) {
    const float cluster = static_cast<float>(i % 5);
    photons.push_back({Vec3(cluster + 0.05f * u(rng), 0.01f * u(rng), 0.05f * u(rng))});
    radii.push_back(0.002f + 0.01f * u(rng));
  }
  for (int i = 0; i < 3000; ++i) {
    photons.push_back({Vec3(5.0f * u(rng), u(rng), u(rng))});
    radii.push_back(0.05f + 0.2f * u(rng));
  }
  for (int i = 0; i < 700; ++i) {
    photons.push_back({Vec3(2.02f, 0.005f, 0.02f)});
    radii.push_back(0.003f);
  }
  std::vector<Vec3> queries;
  for (int q = 0; q < 300; ++q) {
    const float cluster = static_cast<float>(q % 5);
    queries.push_back(q % 2 ? Vec3(cluster + 0.05f * u(rng), 0.005f, 0.05f * u(rng))
                            : Vec3(5.0f * u(rng), u(rng), u(rng)));
  }
  queries.push_back({2.02f, 0.005f, 0.02f});  // inside the pile
  const auto visits = [&](const PhotonDiscs& discs) {
    std::vector<std::vector<Vec3>> all;
    for (const Vec3& x : queries) {
      std::vector<Vec3>& v = all.emplace_back();
      discs.covering(x, [&](const PhotonDiscs::Disc& d, float, float) { v.push_back(d.position); });
    }
    return all;
  };
  const std::vector<std::vector<Vec3>> one = visits(PhotonDiscs(photons, radii, 1));
  size_t found = 0;
  for (size_t q = 0; q < queries.size(); ++q) {
    size_t expected = 0;
    for (size_t i = 0; i < photons.size(); ++i) {
      const Vec3 d = queries[q] - photons[i].position;
      expected += glm::dot(d, d) < radii[i] * radii[i];
    }
    ASSERT_EQ(one[q].size(), expected) << "query " << q;
    found += expected;
  }
  EXPECT_GT(one.back().size(), 700u);  // the whole pile
  EXPECT_GT(found, 5000u);
  for (int threads : {2, 3, 8}) {
    EXPECT_EQ(visits(PhotonDiscs(photons, radii, threads)), one) << threads << " threads";
  }
}

// The walks go depth first, and the slots are laid out depth first: every walk visits its
// discs in slot order (ascending addresses), which is what makes a gather's sum the same
// whatever shape the tree is walked in (binary, or two levels at a time). Maps of 1 to 70
// photons give a root that is one leaf, and nodes with fewer than four entries.
TEST(PhotonDiscs, WalksVisitDiscsInSlotOrderAndFindEveryOneForSmallMaps) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (const int count : {1, 2, 7, 8, 9, 16, 17, 33, 70, 5000}) {
    std::vector<Photon> photons(static_cast<size_t>(count));
    std::vector<float> radii(photons.size());
    for (size_t i = 0; i < photons.size(); ++i) {
      photons[i].position = Vec3(u(rng), 1e-3f * u(rng), u(rng));
      radii[i] = 0.02f + 0.3f * u(rng) * u(rng);
    }
    const PhotonDiscs discs(photons, radii);
    PixelFootprint f{true, Vec3(0.01f, 0.0f, 0.0f), Vec3(0.0f, 0.0f, 0.01f)};
    const PixelFootprint::Test test = f.test(Vec3(0.0f, 1.0f, 0.0f));
    for (int q = 0; q < 50; ++q) {
      const Vec3 x(u(rng), 0.0f, u(rng));
      std::vector<const PhotonDiscs::Disc*> covering, reaching;
      discs.covering(x, [&](const PhotonDiscs::Disc& d, float, float) { covering.push_back(&d); });
      discs.reaching(x, 0.02f, 0.04f, 0.0001f, test.grownBy(0.01f),
                     [&](const PhotonDiscs::Disc& d, float, float) { reaching.push_back(&d); });
      for (const auto* visited : {&covering, &reaching}) {
        for (size_t i = 1; i < visited->size(); ++i) {
          ASSERT_LT((*visited)[i - 1], (*visited)[i]) << count << " photons, query " << q;
        }
      }
      size_t expected = 0;
      for (size_t i = 0; i < photons.size(); ++i) {
        const Vec3 d = x - photons[i].position;
        expected += glm::dot(d, d) < radii[i] * radii[i];
      }
      ASSERT_EQ(covering.size(), expected) << count << " photons, query " << q;
    }
  }
}

}  // namespace
}  // namespace prism
