// Display encoding for 8-bit outputs (PNG, the viewer): exposure, clamp to [0, 1], then the
// sRGB transfer curve (IEC 61966-2-1). EXR output never goes through here.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

#include "math/Vec.h"

namespace prism {

inline float linearToSrgb(float linear) {
  if (!(linear > 0.0f)) return 0.0f;  // also maps NaN to black
  if (linear >= 1.0f) return 1.0f;
  return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

inline float srgbToLinear(float encoded) {
  return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

inline uint8_t toDisplayByte(float radiance, float exposure) {
  return static_cast<uint8_t>(std::lround(255.0f * linearToSrgb(radiance * exposure)));
}

// The same encoding as toDisplayByte, an order of magnitude faster for whole images: the
// radiance at which each byte value begins is precomputed (with the exposure folded in), and a
// pixel's byte is found by binary search instead of evaluating pow().
class DisplayEncoder {
 public:
  explicit DisplayEncoder(float exposure) {
    for (int b = 1; b < 256; ++b) {
      thresholds_[b - 1] = srgbToLinear((static_cast<float>(b) - 0.5f) / 255.0f) / exposure;
    }
  }

  uint8_t operator()(float radiance) const {
    // Counts the thresholds at or below the radiance; NaN compares false and gives 0.
    const auto it = std::upper_bound(thresholds_.begin(), thresholds_.end(), radiance,
                                     [](float value, float t) { return !(value >= t); });
    return static_cast<uint8_t>(it - thresholds_.begin());
  }

 private:
  std::array<float, 255> thresholds_;
};

}  // namespace prism
