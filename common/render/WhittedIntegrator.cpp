#include "render/WhittedIntegrator.h"

#include <span>

#include "math/RayOffset.h"
#include "scene/PrimitiveRef.h"
#include "shading/LightFalloff.h"
#include "shading/MaterialEval.h"
#include "shading/Optics.h"
#include "shading/SpecularSplit.h"
#include "util/ScratchArray.h"

namespace prism {

bool WhittedIntegrator::towardsLight(const SurfaceHit& s, const PointLightDesc& light,
                                     LightPath& path, Ray& shadow) {
  const Vec3 toLight = light.position - s.position;
  path.distance = glm::length(toLight);
  if (!(path.distance > 0.0f)) return false;
  path.direction = toLight / path.distance;
  // A light below the geometric surface cannot reach it, whatever the shading normal says.
  if (glm::dot(s.geometricNormal, path.direction) <= 0.0f) return false;
  path.cosTheta = glm::dot(s.shadingNormal, path.direction);
  if (path.cosTheta <= 0.0f) return false;
  shadow.origin = s.rayOrigin(path.direction);
  shadow.direction = path.direction;
  shadow.tMin = 0.0f;
  shadow.tMax = shadowRayLength(glm::length(light.position - shadow.origin));
  return true;
}

Color WhittedIntegrator::reflectance(const ShadingPoint& p, const LightPath& path,
                                     const Vec3& toViewer) {
  const MaterialDesc& m = *p.material;
  Color reflected = p.albedo * (kInvPi * path.cosTheta);
  if (!isBlack(m.specular)) {
    const float rv = glm::dot(reflect(-path.direction, p.surface.shadingNormal), toViewer);
    if (rv > 0.0f) reflected += m.specular * std::pow(rv, m.shininess);
  }
  return reflected;
}

Color WhittedIntegrator::lightReflected(const PointLightDesc& light, const LightPath& path,
                                        const Color& reflectance) {
  // Irradiance factor I·att(d); times albedo/π·cosθ it is Lambertian radiance in W/(m²·sr).
  const Color lightAtSurface =
      light.intensity * attenuationFactor(light.attenuation, path.distance);
  return lightAtSurface * reflectance;
}

Color WhittedIntegrator::directLighting(const ShadingPoint& p, const Vec3& toViewer,
                                        RayCounters& counters) const {
  Color result(0.0f);
  for (const PointLightDesc& light : scene_.lights()) {
    LightPath path;
    Ray shadow;
    if (!towardsLight(p.surface, light, path, shadow)) continue;
    const Color reflected = reflectance(p, path, toViewer);
    if (isBlack(reflected)) continue;  // nothing to shadow (see reflectance())
    ++counters.shadow;
    if (scene_.occluded(shadow)) continue;
    result += lightReflected(light, path, reflected);
  }
  return result;
}

void WhittedIntegrator::shadingPoint(const Ray& ray, const HitRecord& hit, ShadingPoint& p) const {
  scene_.surface(ray, hit, p.surface);
  p.material = &scene_.materials()[p.surface.material];
  p.albedo = diffuseAlbedo(*p.material, p.surface.position);
}

bool WhittedIntegrator::litDirectly(const ShadingPoint& p) const {
  return terms_.direct && (!isBlack(p.albedo) || !isBlack(p.material->specular));
}

Color WhittedIntegrator::surfaceRadiance(const ShadingPoint& p, const Color& directLight,
                                         const PixelFootprint& footprint) const {
  Color result(0.0f);
  if (terms_.direct) {
    result = p.material->ambient * scene_.ambientLight();
    if (litDirectly(p)) result += directLight;
  }
  if (terms_.caustics && (p.surface.caustic & kReceivesCaustics) && !isBlack(p.albedo)) {
    result += p.albedo * kInvPi * terms_.caustics->irradianceAt(p.surface, footprint);
  }
  return result;
}

template <class Send>
void WhittedIntegrator::forEachBounce(const Ray& ray, const HitRecord& hit, const ShadingPoint& p,
                                      const PixelFootprint& footprint, int depth,
                                      const Color& weight, const RayDifferential& differential,
                                      RayCounters& counters, Send&& send) const {
  const RenderSettings& settings = scene_.settings();
  if (depth >= settings.maxDepth) return;
  const SurfaceHit& s = p.surface;
  const MaterialDesc& m = *p.material;
  // Planes, flat triangles and spheres pass the pixel's footprint on, turned by their curvature;
  // other curved surfaces (cones, smooth-shaded meshes) end it, and estimates past them are
  // taken at the point. So does a footprint too wide for its sphere: the turn is first order, and
  // over a footprint of reach ρ on a ball of radius R the neglected terms are about ρ/2R of the
  // spread it gives (the surface leaves the footprint's plane by ρ²/2R). Past ρ = R/4 (an eighth)
  // the model stops standing for the pixel's rays, and a pixel holding a whole small mirror ball
  // would send them over radians: gathers past it averaged the photons of much of the scene
  // (sphereflakes: over ten thousand per estimate).
  const PrimitiveKind kind = PrimitiveRef::kind(hit.primitive);
  bool turnKnown = kind == PrimitiveKind::Plane ||
                   (kind == PrimitiveKind::Triangle && s.shadingNormal == s.geometricNormal);
  RayDifferential::Turn turn;
  if (kind == PrimitiveKind::Sphere && footprint.valid) {
    const float radius = scene_.spheres()[PrimitiveRef::index(hit.primitive)].radius;
    if (footprint.reach() <= kMaxFootprintReachOnSphere * radius) {
      turn = RayDifferential::sphereTurn(footprint, (s.frontFace ? 1.0f : -1.0f) / radius);
      turnKnown = true;
    }
  }

  const auto [reflectWeight, transmitWeight, refracted] = splitSpecular(m, s, ray.direction);

  const Color reflectContribution = weight * reflectWeight;
  if (maxComponent(reflectContribution) > settings.minContribution) {
    const Vec3 direction = reflectedDirection(s, ray.direction);
    ++counters.secondary;
    send(s.rayOrigin(direction), direction, reflectWeight, reflectContribution,
         turnKnown ? differential.reflected(footprint, ray.direction, s.geometricNormal, turn)
                   : RayDifferential{});
  }

  const Color transmitContribution = weight * transmitWeight;
  if (refracted && maxComponent(transmitContribution) > settings.minContribution) {
    ++counters.secondary;
    const float eta = s.frontFace ? 1.0f / m.ior : m.ior;
    send(s.rayOrigin(*refracted), *refracted, transmitWeight, transmitContribution,
         turnKnown ? differential.refracted(footprint, ray.direction, s.shadingNormal, turn,
                                            *refracted, eta)
                   : RayDifferential{});
  }
}

Color WhittedIntegrator::radiance(const Ray& ray, int depth, const Color& weight,
                                  RayCounters& counters,
                                  const RayDifferential& differential) const {
  HitRecord hit;
  if (!scene_.intersect(ray, hit)) {
    return escaped(ray);
  }
  return shade(ray, hit, depth, weight, counters, differential);
}

Color WhittedIntegrator::escaped(const Ray& ray) const {
  return terms_.direct ? scene_.escapedRadiance(ray.direction) : Color(0.0f);
}

Color WhittedIntegrator::shade(const Ray& ray, const HitRecord& hit, int depth, const Color& weight,
                               RayCounters& counters, const RayDifferential& differential) const {
  ShadingPoint p;
  shadingPoint(ray, hit, p);
  const Color direct = litDirectly(p) ? directLighting(p, -ray.direction, counters) : Color(0.0f);
  const PixelFootprint footprint =
      differential.footprint(ray.direction, hit.t, p.surface.geometricNormal);
  Color result = surfaceRadiance(p, direct, footprint);
  forEachBounce(ray, hit, p, footprint, depth, weight, differential, counters,
                [&](const Vec3& origin, const Vec3& direction, const Color& scale,
                    const Color& contribution, const RayDifferential& onwardDifferential) {
                  result += scale * radiance(Ray{origin, direction}, depth + 1, contribution,
                                             counters, onwardDifferential);
                });
  return result;
}

void WhittedIntegrator::radiance8(const Ray* rays, int count, Color* results,
                                  RayCounters& counters) const {
  Color weights[Scene::kPacketSize];
  for (int i = 0; i < count; ++i) weights[i] = Color(1.0f);
  radiancePacket(rays, count, (1u << count) - 1u, 0, weights, results, counters);
}

void WhittedIntegrator::radiancePacket(const Ray* rays, int count, uint32_t live, int depth,
                                       const Color* weights, Color* results,
                                       RayCounters& counters) const {
  constexpr int kSize = Scene::kPacketSize;
  // Bounces that spread out (off curved mirrors) or leave few rays cost a packet more than they
  // share: those rays go on alone.
  if (depth > 0 &&
      (__builtin_popcount(live) < kMinPacketRays || !Scene::coherentDirections(rays, live))) {
    for (uint32_t m = live; m != 0; m &= m - 1) {
      const int i = __builtin_ctz(m);
      results[i] = radiance(rays[i], depth, weights[i], counters);
    }
    return;
  }
  ScratchArray<HitRecord, kSize> hits;
  bool found[kSize];
  scene_.intersect8(rays, count, hits.data(), found);

  ScratchArray<ShadingPoint, kSize> points;
  bool lit[kSize];
  bool anyLit = false;
  Color direct[kSize];
  for (int i = 0; i < count; ++i) {
    lit[i] = false;
    direct[i] = Color(0.0f);
    if (!found[i]) continue;
    shadingPoint(rays[i], hits[i], points[i]);
    lit[i] = litDirectly(points[i]);
    anyLit = anyLit || lit[i];
  }
  // Direct light one light at a time, its shadow rays as one packet; each point adds the
  // lights up in the order directLighting() does. Rays left out of a packet get tMax below tMin.
  // A packet where no ray met a lit surface has no shadow rays to trace: nearly half of the
  // default scene's (the floor's reflections, into the sky).
  const std::span<const PointLightDesc> lights =
      anyLit ? std::span<const PointLightDesc>(scene_.lights()) : std::span<const PointLightDesc>();
  for (const PointLightDesc& light : lights) {
    ScratchArray<LightPath, kSize> paths;
    Ray shadows[kSize];
    Color reflected[kSize];
    bool towards[kSize];
    bool anyTowards = false;
    for (int i = 0; i < count; ++i) {
      towards[i] = lit[i] && towardsLight(points[i].surface, light, paths[i], shadows[i]);
      if (towards[i]) {
        reflected[i] = reflectance(points[i], paths[i], -rays[i].direction);
        towards[i] = !isBlack(reflected[i]);
      }
      if (!towards[i]) shadows[i].tMax = -1.0f;
      counters.shadow += towards[i] ? 1 : 0;
      anyTowards = anyTowards || towards[i];
    }
    if (!anyTowards) continue;
    bool blocked[kSize];
    scene_.occluded8(shadows, count, blocked);
    for (int i = 0; i < count; ++i) {
      if (towards[i] && !blocked[i]) direct[i] += lightReflected(light, paths[i], reflected[i]);
    }
  }

  // The bounces: each ray's reflected ray, then its refracted one (the order shade() adds them
  // in), k for the k-th bounce of a ray.
  Ray onward[2][kSize];
  Color scale[2][kSize], contribution[2][kSize];
  uint32_t bouncing[2] = {0, 0};
  for (uint32_t m = live; m != 0; m &= m - 1) {
    const int i = __builtin_ctz(m);
    if (!found[i]) {
      results[i] = escaped(rays[i]);
      continue;
    }
    results[i] = surfaceRadiance(points[i], direct[i], {});
    int k = 0;
    forEachBounce(rays[i], hits[i], points[i], {}, depth, weights[i], {}, counters,
                  [&](const Vec3& origin, const Vec3& direction, const Color& rayScale,
                      const Color& rayContribution, const RayDifferential&) {
                    // Built here from origin and direction: a whole Ray built by the caller
                    // and copied in was read back before its stores had landed (a
                    // store-forwarding stall).
                    onward[k][i] = Ray{origin, direction};
                    scale[k][i] = rayScale;
                    contribution[k][i] = rayContribution;
                    bouncing[k] |= 1u << i;
                    ++k;
                  });
  }
  // Every ray's first bounce as one packet, then its second: a ray still adds its reflection
  // before its refraction. Lanes without a bounce are left out (tMax below tMin).
  for (int k = 0; k < 2 && bouncing[k] != 0; ++k) {
    for (int i = 0; i < count; ++i) {
      if (!(bouncing[k] >> i & 1u)) onward[k][i].tMax = -1.0f;
    }
    Color arriving[kSize];
    radiancePacket(onward[k], count, bouncing[k], depth + 1, contribution[k], arriving, counters);
    for (uint32_t m = bouncing[k]; m != 0; m &= m - 1) {
      const int i = __builtin_ctz(m);
      results[i] += scale[k][i] * arriving[i];
    }
  }
}

}  // namespace prism
