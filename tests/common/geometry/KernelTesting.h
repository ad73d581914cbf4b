// What the tests of the SIMD kernels share: random points in a box, and bit-for-bit comparison
// of floats (the kernels must reproduce their scalar twins exactly, -0 and NaN included).
#pragma once

#include <cstring>

#include "math/Random.h"
#include "math/Vec.h"

namespace prism::test {

inline Vec3 randomVec(Pcg32& rng, float lo, float hi) {
  return {lo + (hi - lo) * rng.nextFloat(), lo + (hi - lo) * rng.nextFloat(),
          lo + (hi - lo) * rng.nextFloat()};
}

inline bool sameBits(float a, float b) {
  return std::memcmp(&a, &b, sizeof(float)) == 0;
}

}  // namespace prism::test
