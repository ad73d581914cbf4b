#include "math/Simd.h"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>

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

// broadcast puts x in every lane bit for bit: -0 stays -0 (an addition to +0 would make it +0),
// and infinities, NaN and subnormals pass unchanged, in four lanes and in eight.
TEST(Simd, BroadcastKeepsEveryBit) {
  const float values[] = {-0.0f,
                          0.0f,
                          1.5f,
                          -3.25e-41f,
                          std::numeric_limits<float>::infinity(),
                          -std::numeric_limits<float>::infinity(),
                          std::numeric_limits<float>::quiet_NaN()};
  for (const float x : values) {
    const simd::Float4 four = simd::broadcast<simd::Float4>(x);
    const simd::Float8 eight = simd::broadcast<simd::Float8>(x);
    for (int i = 0; i < 8; ++i) {
      const float fourLane = four[i % 4], eightLane = eight[i];
      EXPECT_EQ(std::memcmp(&fourLane, &x, sizeof x), 0) << x << " lane " << i % 4;
      EXPECT_EQ(std::memcmp(&eightLane, &x, sizeof x), 0) << x << " lane " << i;
    }
  }
}

// laneCount agrees with a count bit by bit on every 16-bit pattern and on patterns spread
// over all 32 bits (the bit-parallel sum carries between its bytes).
TEST(Simd, LaneCountIsTheNumberOfSetBits) {
  const auto counted = [](uint32_t mask) {
    int n = 0;
    for (int bit = 0; bit < 32; ++bit) n += (mask >> bit) & 1u;
    return n;
  };
  for (uint32_t mask = 0; mask < (1u << 16); ++mask) {
    ASSERT_EQ(simd::laneCount(mask), counted(mask)) << mask;
  }
  uint32_t state = 12345u;
  for (int i = 0; i < 100000; ++i) {
    state = state * 1664525u + 1013904223u;
    ASSERT_EQ(simd::laneCount(state), counted(state)) << state;
  }
  EXPECT_EQ(simd::laneCount(0xffffffffu), 32);
}

}  // namespace
}  // namespace prism
