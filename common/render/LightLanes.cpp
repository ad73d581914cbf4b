#include "render/LightLanes.h"

#include <cmath>

#include "math/RayOffset.h"
#include "shading/LightFalloff.h"

namespace prism {

namespace {

using namespace lanes;

// The lanes of one vector: lightPathLanes' arithmetic but for the highlight's pow(), which is
// left to the caller (rv: r·v, the highlight's cosine). Writes every lane's shadow ray, as if
// the light reached it. Returns the lanes the light reaches.
uint32_t pathsInVector(const ShadingLanes& s, int first, const PointLightDesc& light,
                       LightPathLanes& paths, float* rv, Ray* shadows) {
  // towardsLight (render/PointLightPath.h): the path, and whether the light can reach the point.
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

  // reflectance (render/PointLightPath.h): albedo/π·cosθ, plus the highlight where r·v > 0.
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
  storeRays(origin, direction, shadowRayLength(simd::sqrtLanes(dot(fromOrigin, fromOrigin))),
            shadows + first);
  return reach << first;
}

}  // namespace

void lightPathLanes(const ShadingLanes& s, uint32_t lanes, int count, const PointLightDesc& light,
                    LightPathLanes& paths, Ray* shadows) {
  constexpr int kLanes = ShadingLanes::kLanes;
  alignas(32) float rv[kLanes], highlight[kLanes] = {};
  uint32_t reach = 0;
  constexpr uint32_t kVectorLanes = (1u << kWidth) - 1u;
  for (int first = 0; first < kLanes; first += kWidth) {
    if ((lanes >> first & kVectorLanes) == 0) continue;  // no point in this vector
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
    if ((reach >> first & kVectorLanes) == 0) continue;
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
    Ray& empty = shadows[simd::firstLane(m)];
    empty.tMin = 0.0f;
    empty.tMax = -1.0f;
  }
}

void addLightLanes(const LightPathLanes& paths, uint32_t unblocked, const PointLightDesc& light,
                   ShadingLanes::Lanes direct[3]) {
  // lightReflected (render/PointLightPath.h): I·att(d) times the reflectance.
  const Attenuation& a = light.attenuation;
  for (int first = 0; first < ShadingLanes::kLanes; first += kWidth) {
    if ((unblocked >> first & ((1u << kWidth) - 1u)) == 0) continue;  // nothing to add here
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
