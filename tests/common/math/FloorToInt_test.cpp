#include "math/FloorToInt.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>

#include "math/Random.h"

namespace prism {
namespace {

// floor(x) cast to an integer, for every kind of float in range: integers and the floats next
// to them on both sides, ±0, halves, values past 2^23 (all integral), and random values of every
// magnitude from 2^-30 to 2^30 with either sign.
TEST(FloorToInt, IsTheFloorOfEveryFloatInRange) {
  std::vector<float> xs = {0.0f,       -0.0f,       0.5f, -0.5f, 1.0f,          -1.0f,
                           8388608.0f, -8388609.0f, 1e9f, -1e9f, 2147483520.0f, -2147483648.0f};
  for (int k = -300; k <= 300; ++k) {
    const float v = static_cast<float>(k) * 0.25f;
    xs.insert(xs.end(), {v, std::nextafter(v, 1e30f), std::nextafter(v, -1e30f)});
  }
  Pcg32 rng(17, 4);
  for (int i = 0; i < 100000; ++i) {
    const float magnitude = std::ldexp(1.0f, static_cast<int>(rng.nextFloat() * 60.0f) - 30);
    xs.push_back((rng.nextFloat() < 0.5f ? -1.0f : 1.0f) * magnitude * (1.0f + rng.nextFloat()));
  }
  for (const float x : xs) {
    ASSERT_EQ(floorToInt<int>(x), static_cast<int>(std::floor(x))) << x;
    ASSERT_EQ(floorToInt<long>(x), static_cast<long>(std::floor(x))) << x;
  }
  EXPECT_EQ(floorToInt<long>(-1e12f), static_cast<long>(std::floor(-1e12f)));
}

}  // namespace
}  // namespace prism
