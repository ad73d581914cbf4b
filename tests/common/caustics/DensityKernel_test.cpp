#include "caustics/DensityKernel.h"

#include <gtest/gtest.h>

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
