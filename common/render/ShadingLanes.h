// A packet's shading points as lanes of vectors (math/Simd.h): one array of eight lanes per
// coordinate, so that the kernels working on all points at once (render/LightLanes.h,
// render/MirrorLanes.h) take one vector operation where the scalar code takes one per point. The
// vector is the widest the build does well: eight lanes with AVX, else four, twice (GCC splits
// an eight-lane comparison without AVX into one scalar comparison per lane). Lane arithmetic
// keeps the scalar code's operations and their order (glm::dot's included), and the build fuses
// no multiply-add, so each lane's result is the scalar result to the bit.
#pragma once

#include <cstdint>

#include "geometry/HitRecord.h"
#include "math/Ray.h"
#include "math/RayRows.h"
#include "math/Simd.h"
#include "scene/SceneDescription.h"
#include "shading/SpecularSplit.h"

namespace prism {

struct ShadingLanes {
  static constexpr int kLanes = 8;
  using Lanes = float[kLanes];

  alignas(32) Lanes position[3], geometricNormal[3], shadingNormal[3], leavingDistance;
  alignas(32) Lanes albedo[3], specular[3], shininess, toViewer[3];
  uint32_t specularLanes = 0;  // lanes whose material has a Phong highlight (specular not black)

  // Lane `lane` is the point s of material m, its diffuse albedo there albedoHere, seen along
  // -toViewerHere.
  void set(int lane, const SurfaceHit& s, const Color& albedoHere, const MaterialDesc& m,
           const Vec3& toViewerHere) {
    for (int a = 0; a < 3; ++a) {
      position[a][lane] = s.position[a];
      geometricNormal[a][lane] = s.geometricNormal[a];
      shadingNormal[a][lane] = s.shadingNormal[a];
      albedo[a][lane] = albedoHere[a];
      specular[a][lane] = m.specular[a];
      toViewer[a][lane] = toViewerHere[a];
    }
    leavingDistance[lane] = s.leavingDistance;
    shininess[lane] = m.shininess;
    specularLanes = (specularLanes & ~(1u << lane)) | (isBlack(m.specular) ? 0u : 1u << lane);
  }
};

namespace lanes {

#if defined(__AVX__)
using V = simd::Float8;
#else
using V = simd::Float4;
#endif
using M = simd::MaskOf<V>;
inline constexpr int kWidth = static_cast<int>(sizeof(V) / sizeof(float));

struct Vec3Lanes {
  V x[3];
};

// Lanes first..first+kWidth-1 of each coordinate.
inline Vec3Lanes load3(const ShadingLanes::Lanes lanes[3], int first) {
  return {{simd::load<V>(lanes[0] + first), simd::load<V>(lanes[1] + first),
           simd::load<V>(lanes[2] + first)}};
}

// glm::dot's order: (a.x·b.x + a.y·b.y) + a.z·b.z.
inline V dot(const Vec3Lanes& a, const Vec3Lanes& b) {
  return a.x[0] * b.x[0] + a.x[1] * b.x[1] + a.x[2] * b.x[2];
}

// Rays first..first+3 of `rays` from four lanes of origins, directions and ends (tMin 0),
// each stored whole (math/RayRows.h).
inline void storeRays(const simd::Float4 origin[3], const simd::Float4 direction[3],
                      simd::Float4 tMax, Ray* rays) {
  simd::storeRays(origin, direction, simd::Float4{}, tMax, rays);
}

// The same for the kWidth lanes of a vector: rays first..first+kWidth-1.
// (Preprocessor branches, as for V: outside a template both arms of an `if constexpr` must
// compile.)
inline void storeRays(const Vec3Lanes& origin, const Vec3Lanes& direction, V tMax, Ray* rays) {
#if defined(__AVX__)
  simd::Float4 o[2][3], d[2][3], t[2];
  for (int a = 0; a < 3; ++a) {
    simd::splitHalves(origin.x[a], o[0][a], o[1][a]);
    simd::splitHalves(direction.x[a], d[0][a], d[1][a]);
  }
  simd::splitHalves(tMax, t[0], t[1]);
  storeRays(o[0], d[0], t[0], rays);
  storeRays(o[1], d[1], t[1], rays + 4);
#else
  storeRays(origin.x, direction.x, tMax, rays);
#endif
}

}  // namespace lanes
}  // namespace prism
