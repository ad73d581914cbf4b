// A caustic with a point focus and an outer fold, against its closed form, scored in radial rings
// 3 pixels wide as tests/bench/sphere_caustic_reference.cpp scores the glass ball: a box about
// the focus keeps its flux when light moves from the focus to the ring around it, a ring does not.
//
// A lens's ray of aperture height h (uniform over the unit disc: h = √u) lands at radius
// ρ = b·h³(4 − 3h): near the axis ρ ∝ h³, spherical aberration's point focus (irradiance
// ∝ ρ^(−4/3)); at the rim dρ/dh = 12b·h²(1 − h) = 0, a fold at ρ = b (irradiance ∝ 1/√(b − ρ)
// inside it, nothing outside). Photons are drawn stratified in (u, φ), as the renderer's
// emission stratifies them per cell; pixels are gathered as the renderer gathers them (the
// pixel's footprint, the samples where PixelSampler puts them, each sample over its stratum's
// cell). Each pixel's exact flux is the same map applied to a dense midpoint grid of (u, φ).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "caustics/GatherRadius.h"
#include "caustics/PhotonGather.h"
#include "math/Random.h"
#include "render/PixelSampler.h"

namespace prism {
namespace {

constexpr float kPixel = 0.003f;         // a pixel's side on the receiver
constexpr double kFold = 20.0 * kPixel;  // b: the fold's radius
constexpr int kHalf = 24;                // pixels each side of the focal one
constexpr int kSide = 2 * kHalf + 1;
constexpr int kRingPixels = 3;
// The focus off its pixel's centre, as a focus generally is.
const Vec3 kFocus(0.3f * kPixel, 0.0f, 0.2f * kPixel);

Vec3 landing(double u, double phi) {
  const double h = std::sqrt(u), rho = kFold * h * h * h * (4.0 - 3.0 * h);
  return kFocus + Vec3(static_cast<float>(rho * std::cos(phi)), 0.0f,
                       static_cast<float>(rho * std::sin(phi)));
}

int pixelOf(const Vec3& p) {  // row-major index, or -1 outside the scored square
  const int px = static_cast<int>(std::floor(p.x / kPixel + 0.5f));
  const int py = static_cast<int>(std::floor(p.z / kPixel + 0.5f));
  if (px < -kHalf || py < -kHalf || px > kHalf || py > kHalf) return -1;
  return (py + kHalf) * kSide + px + kHalf;
}

// Each pixel's share of the total flux, from 4000 × 4000 midpoints of (u, φ).
const std::vector<double>& exactPixelFlux() {
  static const std::vector<double> flux = [] {
    constexpr int kN = 4000;
    std::vector<double> f(kSide * kSide, 0.0);
    for (int i = 0; i < kN; ++i)
      for (int j = 0; j < kN; ++j) {
        const int at = pixelOf(landing((i + 0.5) / kN, 2.0 * M_PI * (j + 0.5) / kN));
        if (at >= 0) f[at] += 1.0 / (static_cast<double>(kN) * kN);
      }
    return f;
  }();
  return flux;
}

// n × n photons of total power 1, one jittered in each cell of (u, φ).
std::shared_ptr<const PhotonMap> stratifiedPhotons(int n, uint64_t seed) {
  Pcg32 rng = Pcg32::forKey(seed, 0, 0);
  std::vector<Photon> photons;
  photons.reserve(static_cast<size_t>(n) * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      Photon p;
      p.position = landing((i + rng.nextFloat()) / n, 2.0 * M_PI * (j + rng.nextFloat()) / n);
      p.power = Color(1.0f / (static_cast<float>(n) * n));
      p.setDirection({0.0f, -1.0f, 0.0f});
      photons.push_back(p);
    }
  return std::make_shared<const PhotonMap>(std::move(photons));
}

// Each pixel's flux (irradiance × pixel area) for a view straight down, spp samples a pixel.
std::vector<double> pixelFlux(const PhotonGather& gather, int spp) {
  const PixelSampler sampler(spp);
  std::vector<double> image(kSide * kSide, 0.0);
  for (int py = -kHalf; py <= kHalf; ++py)
    for (int px = -kHalf; px <= kHalf; ++px) {
      Pcg32 rng =
          Pcg32::forKey(0, static_cast<uint64_t>(px + 1000), static_cast<uint64_t>(py + 1000));
      double sum = 0.0;
      for (int i = 0; i < spp; ++i) {
        const Vec2 offset = sampler.offset(i, rng);
        SurfaceHit hit;
        hit.position = Vec3((px - 0.5f + offset.x) * kPixel, 0.0f, (py - 0.5f + offset.y) * kPixel);
        hit.geometricNormal = Vec3(0.0f, 1.0f, 0.0f);
        PixelFootprint footprint;
        footprint.valid = true;
        footprint.a = Vec3(kPixel, 0.0f, 0.0f);
        footprint.b = Vec3(0.0f, 0.0f, kPixel);
        if (spp > 1) {  // as TileRenderer: each sample stands for its stratum's cell
          footprint.cell = sampler.stratumSize();
          footprint.toCellCentre = sampler.stratumCentre(i) - offset;
        }
        sum += gather.irradianceAt(hit, footprint).x;
      }
      image[(py + kHalf) * kSide + px + kHalf] = sum / spp * kPixel * kPixel;
    }
  return image;
}

// Pixels grouped by their centre's distance from the focus into rings of kRingPixels.
std::vector<double> rings(const std::vector<double>& image) {
  std::vector<double> out;
  for (int py = -kHalf; py <= kHalf; ++py)
    for (int px = -kHalf; px <= kHalf; ++px) {
      const double dx = px - kFocus.x / kPixel, dy = py - kFocus.z / kPixel;
      const size_t ring = static_cast<size_t>(std::sqrt(dx * dx + dy * dy) / kRingPixels);
      if (ring >= out.size()) out.resize(ring + 1, 0.0);
      out[ring] += image[(py + kHalf) * kSide + px + kHalf];
    }
  return out;
}

// The ring just inside the fold, which holds its brightest light.
size_t foldRing() {
  return static_cast<size_t>((kFold / kPixel - 0.5) / kRingPixels);
}

PhotonGatherSettings gatherOfPass(int pass) {
  CausticSettings c;  // k = 100, cone filter, α = 0.7: the render defaults
  PhotonGatherSettings g;
  for (int i = 1; i <= pass; ++i) g = progressiveGather(c, 0.1f, i, g);
  return g;
}

class FocusAndFoldClassic : public testing::TestWithParam<int> {};

// One pass of 256² photons (k = 100): the innermost ring (the focus) within 1 % at 1, 4 and 16
// spp and every other ring holding 2 % of the light within 1 %, except the two either side of
// the fold, between which the kernels may move light: together within 1 %. (Dense photons:
// about 45 a pixel at the fold. The glass ball's fold gets a tenth of a photon a pixel, and its
// kernels of k = 100 are wider than the fold's rings: docs/accuracy.md.)
TEST_P(FocusAndFoldClassic, TheFocusRingAndTheLightAcrossTheFoldAreExact) {
  const int spp = GetParam();
  const PhotonGather gather(stratifiedPhotons(256, 7), gatherOfPass(1), 1);
  const std::vector<double> got = rings(pixelFlux(gather, spp)), exact = rings(exactPixelFlux());
  ASSERT_EQ(got.size(), exact.size());
  if (std::getenv("PRINT_RINGS"))
    for (size_t k = 0; k < exact.size(); ++k)
      std::printf("ring %zu exact %.5f ratio %.4f\n", k, exact[k], got[k] / exact[k]);
  const size_t fold = foldRing();
  EXPECT_NEAR(got[0] / exact[0], 1.0, 0.01) << "the focus ring holds " << exact[0];
  for (size_t k = 1; k < exact.size(); ++k) {
    if (exact[k] < 0.02 || k == fold || k == fold + 1) continue;
    EXPECT_NEAR(got[k] / exact[k], 1.0, 0.01) << "ring " << k << " of " << exact[k];
  }
  EXPECT_NEAR((got[fold] + got[fold + 1]) / (exact[fold] + exact[fold + 1]), 1.0, 0.01)
      << "across the fold";
}

INSTANTIATE_TEST_SUITE_P(SamplesPerPixel, FocusAndFoldClassic, testing::Values(1, 4, 16),
                         [](const testing::TestParamInfo<int>& info) {
                           return std::to_string(info.param) + "Spp";
                         });

// Progressive passes converge where the caustic is sharpest: the mean of 64 passes is no worse
// than the mean of its first 8 in any ring holding 0.5 % of the light, beyond 3 standard errors
// of the 8 (from the spread of the passes), and at the focus and the fold's ring it is better or
// within that noise. An estimate that drifted as the radii shrank below a pixel (a floor on the
// radius, sequences alike across passes, running sums losing precision, footprint averaging
// of sub-pixel kernels) would fail it.
TEST(FocusAndFoldProgressive, SixtyFourPassesAreNoWorseThanEightInAnyRing) {
  constexpr int kSpp = 4, kFew = 8, kMany = 64;
  std::vector<std::vector<double>> perPass;
  PhotonGatherSettings g;
  CausticSettings c;
  for (int pass = 1; pass <= kMany; ++pass) {
    g = progressiveGather(c, 0.1f, pass, g);
    const PhotonGather gather(stratifiedPhotons(128, 1000 + pass), g, 1);
    perPass.push_back(rings(pixelFlux(gather, kSpp)));
  }
  const std::vector<double> exact = rings(exactPixelFlux());
  const auto meanOf = [&](int passes, size_t k) {
    double s = 0.0;
    for (int p = 0; p < passes; ++p) s += perPass[p][k];
    return s / passes;
  };
  const auto standardError = [&](int passes, size_t k) {
    const double m = meanOf(passes, k);
    double s2 = 0.0;
    for (int p = 0; p < passes; ++p) s2 += (perPass[p][k] - m) * (perPass[p][k] - m);
    return std::sqrt(s2 / (passes - 1) / passes);
  };
  const size_t fold = foldRing();
  for (size_t k = 0; k < exact.size(); ++k) {
    if (exact[k] < 0.005 && k != fold) continue;
    const double few = std::abs(meanOf(kFew, k) / exact[k] - 1.0);
    const double many = std::abs(meanOf(kMany, k) / exact[k] - 1.0);
    const double noise = standardError(kFew, k) / exact[k];
    if (std::getenv("PRINT_RINGS"))
      std::printf("ring %zu exact %.5f 8: %.5f 64: %.5f se8 %.5f\n", k, exact[k], few, many, noise);
    EXPECT_LE(many, few + 3.0 * noise)
        << "ring " << k << ": 64 passes off by " << many << ", 8 passes by " << few
        << " (standard error " << noise << ")";
  }
  EXPECT_NEAR(meanOf(kMany, 0) / exact[0], 1.0, 0.005) << "the focus after 64 passes";
  EXPECT_LT(std::abs(meanOf(kMany, fold) / exact[fold] - 1.0),
            std::abs(meanOf(kFew, fold) / exact[fold] - 1.0))
      << "the fold's ring converges";
}

}  // namespace
}  // namespace prism
