// Four triangles stored as a structure of arrays, the unit the SIMD triangle tests
// (TriangleMollerTrumbore4.h, TriangleWatertight4.h) read. The pack keeps the vertices
// themselves: the watertight test needs them exact, and Möller–Trumbore's edges v1 − v0 and
// v2 − v0 computed from them in the lanes are bit for bit the edges the scalar test computes.
#pragma once

#include <cstdint>
#include <limits>

#include "geometry/Triangle.h"
#include "math/Simd.h"

namespace prism {

struct alignas(16) TrianglePack4 {
  static constexpr int kWidth = 4;
  // Vertices by coordinate: v0[axis][lane]. Unused lanes hold NaN, which every test rejects
  // (a NaN distance fails t > tMin) without taking any slow path.
  float v0[3][kWidth];
  float v1[3][kWidth];
  float v2[3][kWidth];
  uint32_t triangle[kWidth] = {};  // index of each lane's triangle in the scene's array

  TrianglePack4() {
    constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
    for (int a = 0; a < 3; ++a) {
      for (int lane = 0; lane < kWidth; ++lane) v0[a][lane] = v1[a][lane] = v2[a][lane] = kNaN;
    }
  }

  void set(int lane, const Triangle& tri, uint32_t index) {
    for (int a = 0; a < 3; ++a) {
      v0[a][lane] = tri.v0[a];
      v1[a][lane] = tri.v1[a];
      v2[a][lane] = tri.v2[a];
    }
    triangle[lane] = index;
  }
};

struct PackHit {
  int lane = -1;
  float t = 0.0f, u = 0.0f, v = 0.0f;
};

// The closest of the lanes in `mask` (smallest t, first lane on a tie), or lane -1: what testing
// the four triangles one after another with a shrinking tMax would pick.
inline PackHit closestLane(uint32_t mask, const simd::Float4& t, const simd::Float4& u,
                           const simd::Float4& v) {
  PackHit best;
  while (mask != 0) {
    const int lane = simd::firstLane(mask);
    mask &= mask - 1;
    if (best.lane < 0 || t[lane] < best.t) best = {lane, t[lane], u[lane], v[lane]};
  }
  return best;
}

}  // namespace prism
