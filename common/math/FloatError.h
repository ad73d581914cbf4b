// Bounds on floating-point rounding error, as pbrt-v4 uses them (Pharr, Jakob and Humphreys,
// "Physically Based Rendering", 4th ed., §6.8; Higham, "Accuracy and Stability of Numerical
// Algorithms", 2002, §3.1): a result computed with n successive float roundings lies within a
// factor (1 ± γ(n)) of the exact one, γ(n) = n·u / (1 − n·u), u = 2⁻²⁴ the unit roundoff.
#pragma once

#include <cmath>
#include <limits>

namespace prism {

inline constexpr float kUnitRoundoff = 0x1p-24f;

inline constexpr float gammaBound(int n) {
  return (static_cast<float>(n) * kUnitRoundoff) / (1.0f - static_cast<float>(n) * kUnitRoundoff);
}

// The neighbouring floats, for rounding a result away from where it must not land.
inline float nextFloatUp(float v) {
  return std::nextafter(v, std::numeric_limits<float>::infinity());
}
inline float nextFloatDown(float v) {
  return std::nextafter(v, -std::numeric_limits<float>::infinity());
}

}  // namespace prism
