// What the lane kernels' tests share: bit-for-bit comparison, and random unit vectors.
#pragma once

#include <cstring>

#include "math/Random.h"
#include "math/Vec.h"

namespace prism {

inline bool sameBits(float a, float b) {
  return std::memcmp(&a, &b, sizeof(float)) == 0;
}

inline bool sameBits(const Vec3& a, const Vec3& b) {
  return sameBits(a.x, b.x) && sameBits(a.y, b.y) && sameBits(a.z, b.z);
}

// Uniform over the sphere (rejection from the cube).
inline Vec3 randomUnit(Pcg32& rng) {
  for (;;) {
    const Vec3 v(2.0f * rng.nextFloat() - 1.0f, 2.0f * rng.nextFloat() - 1.0f,
                 2.0f * rng.nextFloat() - 1.0f);
    const float length = glm::length(v);
    if (length > 0.1f && length <= 1.0f) return v / length;
  }
}

}  // namespace prism
