#include "render/LightLanes.h"

#include <cmath>
#include <cstddef>

#include "math/RayOffset.h"
#include "shading/LightFalloff.h"

namespace prism {

namespace {

// The vector the build does best: eight lanes with AVX, four (twice) without.
#if defined(__AVX__)
using V = simd::Float8;
#else
using V = simd::Float4;
#endif
using M = simd::MaskOf<V>;
constexpr int kWidth = static_cast<int>(sizeof(V) / sizeof(float));

struct Vec3Lanes {
  V x[3];
};

// Lanes first..first+kWidth-1 of each coordinate.
Vec3Lanes load3(const ShadingLanes::Lanes lanes[3], int first) {
  return {{simd::load<V>(lanes[0] + first), simd::load<V>(lanes[1] + first),
           simd::load<V>(lanes[2] + first)}};
}

// glm::dot's order: (a.x·b.x + a.y·b.y) + a.z·b.z.
V dot(const Vec3Lanes& a, const Vec3Lanes& b) {
  return a.x[0] * b.x[0] + a.x[1] * b.x[1] + a.x[2] * b.x[2];
}

// Rays first..first+3 of `rays` from four lanes of origins, directions and lengths (tMin 0):
// each ray is two rows of four floats, transposed from the lanes in registers and stored whole,
// so that the packet's constructor (RayPacket8), reading them back four floats at a time, does
// not wait on eight single-float stores per ray.
void storeRays(const simd::Float4 origin[3], const simd::Float4 direction[3], simd::Float4 tMax,
               Ray* rays) {
  static_assert(sizeof(Ray) == 8 * sizeof(float) && offsetof(Ray, tMax) == 7 * sizeof(float));
  simd::Float4 low[4] = {origin[0], origin[1], origin[2], direction[0]};
  simd::Float4 high[4] = {direction[1], direction[2], simd::Float4{}, tMax};
  simd::transpose(low[0], low[1], low[2], low[3]);
  simd::transpose(high[0], high[1], high[2], high[3]);
  for (int k = 0; k < 4; ++k) {
    float* ray = reinterpret_cast<float*>(&rays[k]);
    simd::store(ray, low[k]);
    simd::store(ray + 4, high[k]);
  }
}

// The lanes of one vector: lightPathLanes' arithmetic but for the highlight's pow(), which is
// left to the caller (rv: r·v, the highlight's cosine). Writes every lane's shadow ray, as if
// the light reached it. Returns the lanes the light reaches.
uint32_t pathsInVector(const ShadingLanes& s, int first, const PointLightDesc& light,
                       LightPathLanes& paths, float* rv, Ray* shadows) {
  // WhittedIntegrator::towardsLight: the path, and whether the light can reach the point.
  const Vec3Lanes position = load3(s.position, first);
  const Vec3Lanes geometric = load3(s.geometricNormal, first);
  const Vec3Lanes shading = load3(s.shadingNormal, first);
  Vec3Lanes toLight, direction;
  for (int a = 0; a < 3; ++a) toLight.x[a] = light.position[a] - position.x[a];
  const V distance = simd::sqrtLanes(dot(toLight, toLight));
  for (int a = 0; a < 3; ++a) direction.x[a] = toLight.x[a] / distance;
  const V facing = dot(geometric, direction);
  const V cosTheta = dot(shading, direction);
  // As the scalar tests are written: a NaN fails `distance > 0` but passes `facing <= 0`.
  const uint32_t reach = simd::laneMask(distance > 0.0f) & ~simd::laneMask(facing <= 0.0f) &
                         ~simd::laneMask(cosTheta <= 0.0f);

  // WhittedIntegrator::reflectance: albedo/π·cosθ, plus the highlight where r·v > 0.
  const V diffuseScale = kInvPi * cosTheta;
  for (int c = 0; c < 3; ++c) {
    simd::store(paths.reflectance[c] + first, simd::load<V>(s.albedo[c] + first) * diffuseScale);
  }
  Vec3Lanes toward, mirrored;
  for (int a = 0; a < 3; ++a) toward.x[a] = -direction.x[a];
  const V twiceCos = 2.0f * dot(toward, shading);
  for (int a = 0; a < 3; ++a) mirrored.x[a] = toward.x[a] - twiceCos * shading.x[a];
  simd::store(rv + first, dot(mirrored, load3(s.toViewer, first)));
  simd::store(paths.distance + first, distance);

  // The shadow ray: from just off the surface on the light's side (facing is not below 0 in
  // the lanes that reach it, so leavingOrigin's step is +leavingDistance along the normal).
  const V leaving = simd::load<V>(s.leavingDistance + first);
  Vec3Lanes origin, fromOrigin;
  for (int a = 0; a < 3; ++a) {
    origin.x[a] = position.x[a] + leaving * geometric.x[a];
    fromOrigin.x[a] = light.position[a] - origin.x[a];
  }
  const V length = shadowRayLength(simd::sqrtLanes(dot(fromOrigin, fromOrigin)));
  if constexpr (kWidth == 4) {
    storeRays(origin.x, direction.x, length, shadows + first);
  } else {
    simd::Float4 o[2][3], d[2][3], t[2];
    for (int a = 0; a < 3; ++a) {
      simd::splitHalves(origin.x[a], o[0][a], o[1][a]);
      simd::splitHalves(direction.x[a], d[0][a], d[1][a]);
    }
    simd::splitHalves(length, t[0], t[1]);
    storeRays(o[0], d[0], t[0], shadows + first);
    storeRays(o[1], d[1], t[1], shadows + first + 4);
  }
  return reach << first;
}

}  // namespace

void ShadingLanes::set(int lane, const SurfaceHit& s, const Color& albedoHere,
                       const MaterialDesc& m, const Vec3& toViewerHere) {
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
  const bool hasSpecular = !(m.specular.x <= 0.0f && m.specular.y <= 0.0f && m.specular.z <= 0.0f);
  specularLanes = (specularLanes & ~(1u << lane)) | (hasSpecular ? 1u << lane : 0u);
}

void lightPathLanes(const ShadingLanes& s, uint32_t lanes, int count, const PointLightDesc& light,
                    LightPathLanes& paths, Ray* shadows) {
  constexpr int kLanes = ShadingLanes::kLanes;
  alignas(32) float rv[kLanes], highlight[kLanes] = {};
  uint32_t reach = 0;
  for (int first = 0; first < kLanes; first += kWidth) {
    reach |= pathsInVector(s, first, light, paths, rv, shadows);
  }
  reach &= lanes;
  // The highlights, pow() lane by lane, then added to the reflectances as vectors.
  uint32_t highlit = 0;
  for (uint32_t m = reach & s.specularLanes; m != 0; m &= m - 1) {
    const int i = simd::firstLane(m);
    if (!(rv[i] > 0.0f)) continue;
    highlight[i] = std::pow(rv[i], s.shininess[i]);
    highlit |= 1u << i;
  }
  uint32_t black = 0;
  for (int first = 0; first < kLanes; first += kWidth) {
    const M add = simd::lanesOf<M>(highlit >> first);
    const V h = simd::load<V>(highlight + first);
    M blackLanes = ~M{};
    for (int c = 0; c < 3; ++c) {
      const V before = simd::load<V>(paths.reflectance[c] + first);
      const V after =
          simd::select<V>(add, before + simd::load<V>(s.specular[c] + first) * h, before);
      simd::store(paths.reflectance[c] + first, after);
      blackLanes &= after <= 0.0f;
    }
    black |= simd::laneMask(blackLanes) << first;
  }
  // Where the light adds exactly nothing, blocked or not, no shadow ray: the ray is left empty.
  paths.towards = reach & ~black;
  for (uint32_t m = ~paths.towards & ((1u << count) - 1u); m != 0; m &= m - 1) {
    shadows[simd::firstLane(m)].tMax = -1.0f;
  }
}

void addLightLanes(const LightPathLanes& paths, uint32_t unblocked, const PointLightDesc& light,
                   ShadingLanes::Lanes direct[3]) {
  // WhittedIntegrator::lightReflected: I·att(d) times the reflectance.
  const Attenuation& a = light.attenuation;
  for (int first = 0; first < ShadingLanes::kLanes; first += kWidth) {
    const V d = simd::load<V>(paths.distance + first);
    const V attenuation = 1.0f / (a.constant + a.linear * d + a.quadratic * d * d);
    const M add = simd::lanesOf<M>(unblocked >> first);
    for (int c = 0; c < 3; ++c) {
      const V before = simd::load<V>(direct[c] + first);
      const V reflected =
          light.intensity[c] * attenuation * simd::load<V>(paths.reflectance[c] + first);
      simd::store(direct[c] + first, simd::select<V>(add, before + reflected, before));
    }
  }
}

}  // namespace prism
