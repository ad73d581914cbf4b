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

// The second coordinate of Sobol's sequence (its generator matrix is Pascal's triangle mod 2).
// With radicalInverse(2, j) as the first, point j of a (0, 2)-sequence in base 2 (Sobol 1967):
// every 2^m consecutive points from a multiple of 2^m put exactly one point in every box
// [a/2^p, (a+1)/2^p) × [b/2^q, (b+1)/2^q) with p + q = m — the best spread two coordinates can
// have, better than Halton's in bases 3 and 5 at a few hundred points.
inline double sobolSecond(uint64_t j) {
  uint64_t direction = uint64_t{1} << 63, bits = 0;
  for (; j > 0; j >>= 1, direction ^= direction >> 1) {
    if (j & 1) bits ^= direction;
  }
  return static_cast<double>(bits >> 11) * 0x1p-53;
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
