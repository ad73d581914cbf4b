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

}  // namespace
}  // namespace prism
