// Four rays written from vector lanes (lane k of each coordinate is ray k). Each ray is two rows
// of four floats (origin, direction x; direction y, z, tMin, tMax), transposed from the lanes
// in registers and stored whole, so that a packet's constructor (RayPacket8), reading them back
// four floats at a time, does not wait on eight single-float stores per ray.
#pragma once

#include <cstddef>

#include "math/Ray.h"
#include "math/Simd.h"

namespace prism::simd {

inline void storeRays(const Float4 origin[3], const Float4 direction[3], Float4 tMin, Float4 tMax,
                      Ray* rays) {
  static_assert(sizeof(Ray) == 8 * sizeof(float) && offsetof(Ray, tMin) == 6 * sizeof(float) &&
                offsetof(Ray, tMax) == 7 * sizeof(float));
  Float4 low[4] = {origin[0], origin[1], origin[2], direction[0]};
  Float4 high[4] = {direction[1], direction[2], tMin, tMax};
  transpose(low[0], low[1], low[2], low[3]);
  transpose(high[0], high[1], high[2], high[3]);
  for (int k = 0; k < 4; ++k) {
    float* ray = reinterpret_cast<float*>(&rays[k]);
    store(ray, low[k]);
    store(ray + 4, high[k]);
  }
}

}  // namespace prism::simd
