#include "render/LightLanes.h"

#include <cmath>

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

// The lanes of one vector: lightPathLanes' arithmetic; the highlight's pow() is left to the
// caller. Returns the lanes the light reaches; rv is r·v, the highlight's cosine.
uint32_t pathsInVector(const ShadingLanes& s, int first, const PointLightDesc& light,
                       LightPathLanes& paths, float* rv, float origins[3][ShadingLanes::kLanes],
                       float directions[3][ShadingLanes::kLanes], float* originDistances) {
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

  // The shadow ray: from just off the surface on the light's side (facing is not below 0 in
  // the lanes that reach it, so leavingOrigin's step is +leavingDistance along the normal).
  const V leaving = simd::load<V>(s.leavingDistance + first);
  Vec3Lanes fromOrigin;
  for (int a = 0; a < 3; ++a) {
    const V origin = position.x[a] + leaving * geometric.x[a];
    simd::store(origins[a] + first, origin);
    simd::store(directions[a] + first, direction.x[a]);
    fromOrigin.x[a] = light.position[a] - origin;
  }
  simd::store(originDistances + first, simd::sqrtLanes(dot(fromOrigin, fromOrigin)));
  simd::store(paths.distance + first, distance);
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
  alignas(32) float rv[kLanes], origins[3][kLanes], directions[3][kLanes], originDistances[kLanes];
  uint32_t reach = 0;
  for (int first = 0; first < kLanes; first += kWidth) {
    reach |= pathsInVector(s, first, light, paths, rv, origins, directions, originDistances);
  }
  reach &= lanes;
  uint32_t towards = 0;
  for (uint32_t m = reach; m != 0; m &= m - 1) {
    const int i = simd::firstLane(m);
    float* reflectance[3] = {paths.reflectance[0], paths.reflectance[1], paths.reflectance[2]};
    if ((s.specularLanes >> i & 1u) && rv[i] > 0.0f) {
      const float highlight = std::pow(rv[i], s.shininess[i]);
      for (int c = 0; c < 3; ++c) reflectance[c][i] += s.specular[c][i] * highlight;
    }
    // Where the light adds exactly nothing, blocked or not, no shadow ray.
    const bool black =
        reflectance[0][i] <= 0.0f && reflectance[1][i] <= 0.0f && reflectance[2][i] <= 0.0f;
    towards |= black ? 0u : 1u << i;
  }
  paths.towards = towards;
  for (int i = 0; i < count; ++i) {
    Ray& shadow = shadows[i];
    if (!(towards >> i & 1u)) {
      shadow.tMax = -1.0f;
      continue;
    }
    shadow.origin = Vec3(origins[0][i], origins[1][i], origins[2][i]);
    shadow.direction = Vec3(directions[0][i], directions[1][i], directions[2][i]);
    shadow.tMin = 0.0f;
    shadow.tMax = shadowRayLength(originDistances[i]);
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
