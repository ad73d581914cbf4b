// The low-discrepancy sequences photon emission draws from (math/LowDiscrepancy.h).
#include "math/LowDiscrepancy.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace prism {
namespace {

TEST(LowDiscrepancy, RadicalInverseMirrorsTheDigits) {
  EXPECT_DOUBLE_EQ(radicalInverse(2, 1), 0.5);
  EXPECT_DOUBLE_EQ(radicalInverse(2, 6), 0.375);      // 110₂ → 0.011₂
  EXPECT_DOUBLE_EQ(radicalInverse(3, 5), 7.0 / 9.0);  // 12₃ → 0.21₃
}

// (radicalInverse(2, j), sobolSecond(j)) is a (0, 2)-sequence in base 2: every 2^m points from a
// multiple of 2^m put exactly one point in every box 2^−p wide and 2^−q high with p + q = m.
TEST(LowDiscrepancy, SobolsFirstTwoCoordinatesPutOnePointInEveryElementaryBox) {
  EXPECT_DOUBLE_EQ(sobolSecond(0), 0.0);
  EXPECT_DOUBLE_EQ(sobolSecond(1), 0.5);
  for (int m : {4, 7, 10}) {
    const uint64_t n = uint64_t{1} << m;
    for (uint64_t start : {uint64_t{0}, n, 5 * n}) {
      for (int p = 0; p <= m; ++p) {
        const int q = m - p;
        std::vector<int> count(n, 0);
        for (uint64_t j = start; j < start + n; ++j) {
          const auto column = static_cast<uint64_t>(radicalInverse(2, j) * (uint64_t{1} << p));
          const auto row = static_cast<uint64_t>(sobolSecond(j) * (uint64_t{1} << q));
          ++count[(row << p) | column];
        }
        int wrong = 0;
        for (int c : count) wrong += c != 1;
        EXPECT_EQ(wrong, 0) << "m " << m << ", start " << start << ", boxes 2^-" << p << " x 2^-"
                            << q;
      }
    }
  }
}

}  // namespace
}  // namespace prism
