// A stored caustic photon: where it landed, the power it carries and the direction it came
// from. 28 bytes; the direction is octahedrally encoded in two 16-bit numbers (Cigolle et al.,
// "A Survey of Efficient Representations for Independent Unit Vectors", JCGT 2014), which is
// plenty for the only use it has: rejecting photons that arrived on the other side of a surface.
#pragma once

#include <cmath>
#include <cstdint>

#include "math/Vec.h"

namespace prism {

struct Photon {
  Vec3 position{0.0f};
  Color power{0.0f};               // W, per channel
  uint16_t direction[2] = {0, 0};  // unit travel direction, octahedral encoding

  void setDirection(const Vec3& d);
  Vec3 directionVector() const;
};

namespace octahedral {

inline uint16_t quantise(float v) {
  return static_cast<uint16_t>(std::lround((std::clamp(v, -1.0f, 1.0f) * 0.5f + 0.5f) * 65535.0f));
}
inline float dequantise(uint16_t q) {
  return static_cast<float>(q) / 65535.0f * 2.0f - 1.0f;
}
inline float signNotZero(float v) {
  return v >= 0.0f ? 1.0f : -1.0f;
}

}  // namespace octahedral

inline void Photon::setDirection(const Vec3& d) {
  using namespace octahedral;
  const float l1 = std::abs(d.x) + std::abs(d.y) + std::abs(d.z);
  float x = d.x / l1, y = d.y / l1;
  if (d.z < 0.0f) {
    const float fx = (1.0f - std::abs(y)) * signNotZero(x);
    const float fy = (1.0f - std::abs(x)) * signNotZero(y);
    x = fx;
    y = fy;
  }
  direction[0] = quantise(x);
  direction[1] = quantise(y);
}

inline Vec3 Photon::directionVector() const {
  using namespace octahedral;
  const float x = dequantise(direction[0]), y = dequantise(direction[1]);
  Vec3 v(x, y, 1.0f - std::abs(x) - std::abs(y));
  if (v.z < 0.0f) {
    const float fx = (1.0f - std::abs(v.y)) * signNotZero(v.x);
    const float fy = (1.0f - std::abs(v.x)) * signNotZero(v.y);
    v.x = fx;
    v.y = fy;
  }
  return glm::normalize(v);
}

static_assert(sizeof(Photon) == 28, "photons travel between ranks as raw 28-byte records");

}  // namespace prism
