#include "accel/Simd.h"

#include <gtest/gtest.h>

namespace prism {
namespace {

// lanesOf is laneMask's inverse: every bit pattern of four and eight lanes gives lanes of all
// ones exactly where its bits are set, and laneMask gives the pattern back.
TEST(Simd, LanesOfSetsExactlyTheLanesOfItsBits) {
  for (uint32_t bits = 0; bits < 16; ++bits) {
    const simd::Int4 m = simd::lanesOf<simd::Int4>(bits);
    for (int i = 0; i < 4; ++i) EXPECT_EQ(m[i], (bits >> i & 1u) ? -1 : 0) << bits << " " << i;
    EXPECT_EQ(simd::laneMask(m), bits);
  }
  for (uint32_t bits = 0; bits < 256; ++bits) {
    const simd::Int8 m = simd::lanesOf<simd::Int8>(bits);
    for (int i = 0; i < 8; ++i) EXPECT_EQ(m[i], (bits >> i & 1u) ? -1 : 0) << bits << " " << i;
    EXPECT_EQ(simd::laneMask(m), bits);
  }
}

}  // namespace
}  // namespace prism
