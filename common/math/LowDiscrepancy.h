// The Halton sequence (Halton 1960): point i has coordinates radicalInverse(b, i) for coprime
// bases b, spreading points far more evenly than independent random numbers do. Photon emission
// uses it (bases 2, 3, 5) so photons cover a light's solid angle like a jittered grid rather
// than at random, which cuts the noise of density estimation, as POV-Ray's grid emission does.
#pragma once

#include <cstdint>

namespace prism {

// The digits of i in base b mirrored about the radix point: 0.d₀d₁d₂… in base b, in [0, 1).
inline double radicalInverse(uint32_t base, uint64_t i) {
  const double inverseBase = 1.0 / base;
  double scale = inverseBase, result = 0.0;
  while (i > 0) {
    result += static_cast<double>(i % base) * scale;
    i /= base;
    scale *= inverseBase;
  }
  return result;
}

// x + shift wrapped into [0, 1) and rounded to a float strictly below 1 (Cranley–Patterson
// rotation: decorrelates sequences that share indices while keeping their even spread).
inline float rotateUnit(double x, float shift) {
  double v = x + shift;
  if (v >= 1.0) v -= 1.0;
  const float f = static_cast<float>(v);
  return f < 1.0f ? f : 0x1.fffffep-1f;
}

}  // namespace prism
