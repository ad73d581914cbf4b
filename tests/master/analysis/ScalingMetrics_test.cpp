#include "master/analysis/ScalingMetrics.h"

#include <gtest/gtest.h>

#include <cmath>

namespace prism {
namespace {

TEST(ScalingMetrics, SpreadIsMedianMinAndMax) {
  const TimingSpread odd = spreadOf({3.0, 1.0, 2.0, 10.0, 2.5});
  EXPECT_DOUBLE_EQ(odd.median, 2.5);
  EXPECT_DOUBLE_EQ(odd.min, 1.0);
  EXPECT_DOUBLE_EQ(odd.max, 10.0);
  EXPECT_DOUBLE_EQ(spreadOf({4.0, 1.0, 2.0, 3.0}).median, 2.5);
  EXPECT_THROW(spreadOf({}), std::invalid_argument);
}

// Synthetic timings: T1 = 10 s; 4 workers in 3.125 s give S = 3.2, E = 0.8 and
// e = (1/3.2 − 1/4)/(1 − 1/4) = 0.0625/0.75 = 1/12.
TEST(ScalingMetrics, SpeedupEfficiencyAndKarpFlattOnSyntheticTimings) {
  const double s = speedupOf(10.0, 3.125);
  EXPECT_DOUBLE_EQ(s, 3.2);
  EXPECT_DOUBLE_EQ(efficiencyOf(s, 4), 0.8);
  EXPECT_NEAR(karpFlattOf(s, 4), 1.0 / 12.0, 1e-12);
  EXPECT_NEAR(karpFlattOf(2.0, 2), 0.0, 1e-12);  // perfect speedup: no serial part
  EXPECT_NEAR(karpFlattOf(1.0, 8), 1.0, 1e-12);  // no speedup at all: all serial
  EXPECT_TRUE(std::isnan(karpFlattOf(1.0, 1)));
}

// Karp–Flatt of a speedup that follows Amdahl's law exactly is the law's serial fraction.
TEST(ScalingMetrics, KarpFlattRecoversAmdahlsSerialFraction) {
  for (double p : {2.0, 3.0, 16.0, 1024.0}) {
    EXPECT_NEAR(karpFlattOf(amdahlSpeedup(0.05, p), p), 0.05, 1e-12) << p;
  }
  EXPECT_DOUBLE_EQ(amdahlSpeedup(0.0, 7.0), 7.0);
  EXPECT_DOUBLE_EQ(amdahlSpeedup(1.0, 7.0), 1.0);
}

TEST(ScalingMetrics, AmdahlFitRecoversTheSerialFractionOfExactPoints) {
  const std::vector<double> p{1, 2, 4, 8, 16};
  std::vector<double> s;
  for (double workers : p) s.push_back(amdahlSpeedup(0.1, workers));
  const AmdahlFit fit = fitAmdahl(p, s);
  EXPECT_NEAR(fit.serialFraction, 0.1, 1e-12);
  EXPECT_NEAR(fit.rmsError, 0.0, 1e-12);
}

TEST(ScalingMetrics, AmdahlFitClampsAndReportsItsError) {
  // Superlinear points would need f < 0: clamped to 0, and the miss shows in the error.
  const AmdahlFit fit = fitAmdahl({2, 4}, {2.2, 4.4});
  EXPECT_DOUBLE_EQ(fit.serialFraction, 0.0);
  EXPECT_NEAR(fit.rmsError, std::sqrt((0.2 * 0.2 + 0.4 * 0.4) / 2), 1e-12);
  EXPECT_DOUBLE_EQ(fitAmdahl({1, 1}, {1, 1}).serialFraction, 0.0);  // p = 1 says nothing
  EXPECT_THROW(fitAmdahl({1, 2}, {1}), std::invalid_argument);
}

}  // namespace
}  // namespace prism
