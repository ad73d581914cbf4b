#include "caustics/DensityKernel.h"

#include <gtest/gtest.h>

#include "math/RayDifferential.h"

namespace prism {
namespace {

// ∫ K(d, r) dA over the disc, by the midpoint rule in the radius: 2π Σ K(d_i) d_i Δd. The
// kernels are polynomials in d of degree ≤ 2, so the rule's error is O(Δd²) ≈ 1e-10 with 10⁵
// steps; float evaluation of K adds ~1e-7 relative. 1e-5 is far above both.
double discIntegral(PhotonFilter filter, float radius) {
  constexpr int kSteps = 100000;
  const double step = radius / static_cast<double>(kSteps);
  double sum = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const double d = (i + 0.5) * step;
    sum += densityKernel(filter, static_cast<float>(d * d), radius * radius) * d;
  }
  return 2.0 * 3.14159265358979323846 * sum * step;
}

class DensityKernelTest : public testing::TestWithParam<PhotonFilter> {};

TEST_P(DensityKernelTest, IntegratesToOneOverTheDisc) {
  for (float radius : {0.01f, 0.5f, 1.0f, 7.0f}) {
    EXPECT_NEAR(discIntegral(GetParam(), radius), 1.0, 1e-5) << radius;
  }
}

TEST_P(DensityKernelTest, IsZeroOnAndOutsideTheRimAndNeverNegative) {
  const float r2 = 0.25f;
  EXPECT_EQ(densityKernel(GetParam(), r2, r2), 0.0f);
  EXPECT_EQ(densityKernel(GetParam(), 1.0001f * r2, r2), 0.0f);
  EXPECT_EQ(densityKernel(GetParam(), 100.0f, r2), 0.0f);
  for (float d2 = 0.0f; d2 < r2; d2 += 0.001f) EXPECT_GE(densityKernel(GetParam(), d2, r2), 0.0f);
}

// kernelShareBelow's closed forms against the kernel integrated over the half-plane x < t·r
// numerically (a 1000 × 1000 midpoint grid over the disc's square, the lines on its cells'
// edges: the rule's error, largest where the box kernel steps at the rim, is below 1e-4).
TEST_P(DensityKernelTest, ShareBelowALineIsTheKernelsMassOnThatSide) {
  constexpr int kSteps = 1000;
  const float radius = 1.0f;
  const double step = 2.0 / kSteps;
  for (const float t : {-1.0f, -0.8f, -0.35f, -0.01f, 0.0f, 0.2f, 0.5f, 0.93f, 1.0f}) {
    double below = 0.0;
    for (int i = 0; i < kSteps; ++i) {
      const double x = -1.0 + (i + 0.5) * step;
      if (x >= t) break;
      for (int j = 0; j < kSteps; ++j) {
        const double y = -1.0 + (j + 0.5) * step;
        below += densityKernel(GetParam(), static_cast<float>(x * x + y * y), radius * radius);
      }
    }
    below *= step * step;
    EXPECT_NEAR(kernelShareBelow(GetParam(), t), below, 5e-4) << "t = " << t;
  }
  EXPECT_EQ(kernelShareBelow(GetParam(), 1.5f), 1.0f);
  EXPECT_EQ(kernelShareBelow(GetParam(), -7.0f), 0.0f);
  EXPECT_FLOAT_EQ(kernelShareBelow(GetParam(), 0.0f), 0.5f);
}

// A row of footprints tiling the plane (parallelograms, skewed) shares each photon out whole:
// the shares of the footprints around it sum to 1 wherever it lies, for photons narrower than
// the footprints and wider.
TEST_P(DensityKernelTest, TilingFootprintsShareAPhotonOutWhole) {
  const Vec3 a(0.01f, 0.0f, 0.0f), b(0.004f, 0.0f, 0.012f);  // a footprint's edges
  const PixelFootprint f{true, a, b};
  const PixelFootprint::Test test = f.test(Vec3(0.0f, 1.0f, 0.0f));
  const float dualALength = glm::length(test.dualA), dualBLength = glm::length(test.dualB);
  for (const float radius : {0.001f, 0.004f, 0.009f, 0.02f}) {
    for (const Vec3 photon :
         {Vec3(0.0f), Vec3(0.0043f, 0.0f, 0.0061f), Vec3(-0.007f, 0.0f, 0.002f)}) {
      float sum = 0.0f;
      for (int i = -5; i <= 5; ++i) {
        for (int j = -5; j <= 5; ++j) {
          const Vec3 q = photon - (float(i) * a + float(j) * b);  // from footprint (i, j)'s centre
          sum += kernelShareOfFootprint(GetParam(), glm::dot(q, test.dualA),
                                        glm::dot(q, test.dualB), dualALength, dualBLength, radius);
        }
      }
      EXPECT_NEAR(sum, 1.0f, 1e-5f)
          << "radius " << radius << ", photon at " << photon.x << ", " << photon.z;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Filters, DensityKernelTest,
                         testing::Values(PhotonFilter::Box, PhotonFilter::Cone,
                                         PhotonFilter::Epanechnikov),
                         [](const auto& info) {
                           switch (info.param) {
                             case PhotonFilter::Box:
                               return "Box";
                             case PhotonFilter::Cone:
                               return "Cone";
                             default:
                               return "Epanechnikov";
                           }
                         });

TEST(DensityKernel, ValuesAtTheCentreAndHalfway) {
  const float r2 = 4.0f;  // r = 2: 1/(π r²) = 1/(4π)
  const float unit = kInvPi / 4.0f;
  EXPECT_FLOAT_EQ(densityKernel(PhotonFilter::Box, 0.0f, r2), unit);
  EXPECT_FLOAT_EQ(densityKernel(PhotonFilter::Box, 1.0f, r2), unit);
  EXPECT_FLOAT_EQ(densityKernel(PhotonFilter::Cone, 0.0f, r2), 3.0f * unit);
  EXPECT_FLOAT_EQ(densityKernel(PhotonFilter::Cone, 1.0f, r2), 1.5f * unit);  // d = r/2
  EXPECT_FLOAT_EQ(densityKernel(PhotonFilter::Epanechnikov, 0.0f, r2), 2.0f * unit);
  EXPECT_FLOAT_EQ(densityKernel(PhotonFilter::Epanechnikov, 1.0f, r2), 1.5f * unit);
}

}  // namespace
}  // namespace prism
