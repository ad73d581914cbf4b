#include "render/WhittedIntegrator.h"

#include <cmath>
#include <new>

#include "accel/PrimitiveRef.h"
#include "math/RayOffset.h"
#include "render/LightLanes.h"
#include "render/MirrorLanes.h"
#include "render/PointLightPath.h"
#include "shading/MaterialEval.h"
#include "shading/SpecularSplit.h"
#include "util/ScratchArray.h"

namespace prism {

Color WhittedIntegrator::directLighting(const ShadingPoint& p, const Vec3& toViewer,
                                        RayCounters& counters) const {
  Color result(0.0f);
  for (const PointLightDesc& light : scene_.lights()) {
    LightPath path;
    Ray shadow;
    if (!towardsLight(p.surface, light, path, shadow)) continue;
    const Color reflected = reflectance(p.surface, p.albedo, *p.material, path, toViewer);
    if (isBlack(reflected)) continue;  // the light adds nothing here, blocked or not
    ++counters.shadow;
    if (scene_.occluded(shadow)) continue;
    result += lightReflected(light, path, reflected);
  }
  return result;
}

void WhittedIntegrator::shadingPoint(const Ray& ray, const HitRecord& hit, const RayCone& cone,
                                     ShadingPoint& p) const {
  scene_.surface(ray, hit, p.surface);
  p.material = &scene_.materials()[p.surface.material];
  p.albedo = diffuseAlbedo(*p.material, p.surface, scene_.textures(), ray.direction,
                           cone.known() ? cone.widthAt(hit.t) : 0.0f);
}

bool WhittedIntegrator::litDirectly(const ShadingPoint& p) const {
  return terms_.direct && (!isBlack(p.albedo) || !isBlack(p.material->specular));
}

bool WhittedIntegrator::receivesCaustics(const ShadingPoint& p) const {
  return terms_.caustics && (p.surface.caustic & kReceivesCaustics) && !isBlack(p.albedo);
}

Color WhittedIntegrator::surfaceRadiance(const ShadingPoint& p, const Color& directLight,
                                         const PixelFootprint& footprint) const {
  if (!receivesCaustics(p)) return surfaceRadiance(p, directLight, nullptr);
  const Color caustic = terms_.caustics->irradianceAt(p.surface, footprint);
  return surfaceRadiance(p, directLight, &caustic);
}

Color WhittedIntegrator::surfaceRadiance(const ShadingPoint& p, const Color& directLight,
                                         const Color* causticIrradiance) const {
  Color result(0.0f);
  if (terms_.direct) {
    result = p.material->ambient * scene_.ambientLight();
    if (litDirectly(p)) result += directLight;
  }
  if (causticIrradiance) result += p.albedo * kInvPi * *causticIrradiance;
  return result;
}

bool WhittedIntegrator::bounceTurn(const HitRecord& hit, const SurfaceHit& s,
                                   const PixelFootprint& footprint,
                                   RayDifferential::Turn& turn) const {
  // Planes, flat shapes (discs), flat triangles and spheres pass the pixel's footprint on, turned
  // by their curvature; other curved surfaces (cones, smooth-shaded meshes) end it, and estimates
  // past them are taken at the point. So does a footprint too wide for its sphere: the turn is
  // first order, and over a footprint of reach ρ on a ball of radius R the neglected terms are
  // about ρ/2R of the spread it gives (the surface leaves the footprint's plane by ρ²/2R). Past ρ =
  // R/4 (an eighth) the model stops standing for the pixel's rays, and a pixel holding a whole
  // small mirror ball would send them over radians: gathers past it averaged the photons of much of
  // the scene (sphereflakes: over ten thousand per estimate).
  const PrimitiveKind kind = PrimitiveRef::kind(hit.primitive);
  if (kind == PrimitiveKind::Plane || isFlatShape(kind) ||
      (kind == PrimitiveKind::Triangle && s.shadingNormal == s.geometricNormal)) {
    return true;
  }
  if (kind == PrimitiveKind::Sphere && footprint.valid) {
    const float radius = scene_.spheres()[PrimitiveRef::index(hit.primitive)].radius;
    if (footprint.reach() <= kMaxFootprintReachOnSphere * radius) {
      turn = RayDifferential::sphereTurn(footprint, (s.frontFace ? 1.0f : -1.0f) / radius);
      return true;
    }
  }
  return false;
}

bool WhittedIntegrator::bounceCurvature(const HitRecord& hit, const SurfaceHit& s, float width,
                                        float& curvature) const {
  // The surfaces bounceTurn passes a footprint on over, for the same reasons: a cone whose
  // half-width passes a quarter of its sphere's radius ends there.
  const PrimitiveKind kind = PrimitiveRef::kind(hit.primitive);
  curvature = 0.0f;
  if (kind == PrimitiveKind::Plane || isFlatShape(kind) ||
      (kind == PrimitiveKind::Triangle && s.shadingNormal == s.geometricNormal)) {
    return true;
  }
  if (kind == PrimitiveKind::Sphere) {
    const float radius = scene_.spheres()[PrimitiveRef::index(hit.primitive)].radius;
    if (0.5f * width <= kMaxFootprintReachOnSphere * radius) {
      curvature = (s.frontFace ? 1.0f : -1.0f) / radius;
      return true;
    }
  }
  return false;
}

template <class Send>
void WhittedIntegrator::forEachBounce(const Ray& ray, const HitRecord& hit, const ShadingPoint& p,
                                      const PixelFootprint& footprint, int depth,
                                      const Color& weight, const RayDifferential& differential,
                                      const RayCone& cone, RayCounters& counters,
                                      Send&& send) const {
  const RenderSettings& settings = scene_.settings();
  if (depth >= settings.maxDepth) return;
  const SurfaceHit& s = p.surface;
  const MaterialDesc& m = *p.material;
  RayDifferential::Turn turn;
  const bool turnKnown = differential.valid && bounceTurn(hit, s, footprint, turn);
  float curvature = 0.0f;
  const bool coneGoesOn = cone.known() && bounceCurvature(hit, s, cone.widthAt(hit.t), curvature);

  const auto [reflectWeight, transmitWeight, refracted] = splitSpecular(m, s, ray.direction);

  const Color reflectContribution = weight * reflectWeight;
  if (maxComponent(reflectContribution) > settings.minContribution) {
    const Vec3 direction = reflectedDirection(s, ray.direction);
    ++counters.secondary;
    send(s.rayOrigin(direction), direction, reflectWeight, reflectContribution,
         turnKnown ? differential.reflected(footprint, ray.direction, s.geometricNormal, turn)
                   : RayDifferential{},
         coneGoesOn ? cone.reflected(hit.t, curvature) : RayCone{});
  }

  const Color transmitContribution = weight * transmitWeight;
  if (refracted && maxComponent(transmitContribution) > settings.minContribution) {
    ++counters.secondary;
    const float eta = s.frontFace ? 1.0f / m.ior : m.ior;
    const float cosI = -glm::dot(ray.direction, s.shadingNormal);
    const float cosT = -glm::dot(*refracted, s.shadingNormal);
    send(s.rayOrigin(*refracted), *refracted, transmitWeight, transmitContribution,
         turnKnown ? differential.refracted(footprint, ray.direction, s.shadingNormal, turn,
                                            *refracted, eta)
                   : RayDifferential{},
         coneGoesOn ? cone.refracted(hit.t, curvature, eta, cosI, cosT) : RayCone{});
  }
}

Color WhittedIntegrator::radiance(const Ray& ray, int depth, const Color& weight,
                                  RayCounters& counters, const RayDifferential& differential,
                                  const RayCone& cone) const {
  HitRecord hit;
  if (!scene_.intersect(ray, hit)) {
    return escaped(ray, cone);
  }
  return shade(ray, hit, depth, weight, counters, differential, cone);
}

Color WhittedIntegrator::escaped(const Ray& ray, const RayCone& cone) const {
  if (!terms_.direct) return Color(0.0f);
  if (!cone.known()) return scene_.escapedRadiance(ray.direction);
  return scene_.escapedRadiance(ray.direction, std::fabs(cone.spread));
}

Color WhittedIntegrator::shade(const Ray& ray, const HitRecord& hit, int depth, const Color& weight,
                               RayCounters& counters, const RayDifferential& differential,
                               const RayCone& cone) const {
  ShadingPoint p;
  shadingPoint(ray, hit, cone, p);
  const Color direct = litDirectly(p) ? directLighting(p, -ray.direction, counters) : Color(0.0f);
  const PixelFootprint footprint =
      differential.footprint(ray.direction, hit.t, p.surface.geometricNormal);
  Color result = surfaceRadiance(p, direct, footprint);
  forEachBounce(
      ray, hit, p, footprint, depth, weight, differential, cone, counters,
      [&](const Vec3& origin, const Vec3& direction, const Color& scale, const Color& contribution,
          const RayDifferential& onwardDifferential, const RayCone& onwardCone) {
        result += scale * radiance(Ray{origin, direction}, depth + 1, contribution, counters,
                                   onwardDifferential, onwardCone);
      });
  return result;
}

void WhittedIntegrator::radiance8(const Ray* rays, int count, Color* results, RayCounters& counters,
                                  const RayCone* cones) const {
  Color weights[Scene::kPacketSize];
  for (int i = 0; i < count; ++i) weights[i] = Color(1.0f);
  radiancePacket(rays, count, (1u << count) - 1u, 0, weights, cones, results, counters);
}

// radiancePacket's parts below are always inlined into it, so that the packet loop compiles as
// one function: GCC then sees radiancePacket call itself and specialises it for depths 0, 1 and
// 2. A call through traceBounces hides the recursion from it, and costs the default frame 0.3 %
// more instructions.

// The bounce rays of a packet: lane i of packet k holds the k-th ray the hit of rays[i] sends on
// (its reflected ray, then its refracted one: the order shade() adds them in).
struct WhittedIntegrator::BouncePackets {
  static constexpr int kSize = Scene::kPacketSize;
  explicit BouncePackets(bool carryCones) : withCones(carryCones) {}

  ScratchArray<Ray, kSize> onward[2];  // rays below count written, or emptied before tracing
  Color scale[2][kSize], contribution[2][kSize];
  // Their cones, where the rays carry them: only the bouncing lanes' are written.
  ScratchArray<RayCone, kSize> cones[2];
  uint32_t bouncing[2] = {0, 0};  // bit i: lane i of packet k holds a ray
  const bool withCones;
};

[[gnu::always_inline]] inline void WhittedIntegrator::directLightingLanes(
    const ShadingLanes& lanes, uint32_t litLanes, int count, Color* direct,
    RayCounters& counters) const {
  constexpr int kSize = Scene::kPacketSize;
  alignas(32) ShadingLanes::Lanes directLanes[3] = {};
  for (const PointLightDesc& light : scene_.lights()) {
    LightPathLanes paths;
    ScratchArray<Ray, kSize> shadows;  // every ray below count written by lightPathLanes
    lightPathLanes(lanes, litLanes, count, light, paths, shadows.data());
    if (paths.towards == 0) continue;
    counters.shadow += static_cast<uint64_t>(simd::laneCount(paths.towards));
    bool blocked[kSize];
    scene_.occluded8(shadows.data(), count, blocked);
    uint32_t unblocked = paths.towards;
    for (int i = 0; i < count; ++i) unblocked &= blocked[i] ? ~(1u << i) : ~0u;
    addLightLanes(paths, unblocked, light, directLanes);
  }
  for (uint32_t m = litLanes; m != 0; m &= m - 1) {
    const int i = __builtin_ctz(m);
    direct[i] = Color(directLanes[0][i], directLanes[1][i], directLanes[2][i]);
  }
}

[[gnu::always_inline]] inline uint32_t WhittedIntegrator::causticEstimates(
    const ShadingPoint* points, uint32_t foundLanes, Color* caustic) const {
  constexpr int kSize = Scene::kPacketSize;
  uint32_t receivingLanes = 0;
  const SurfaceHit* receivers[kSize];
  int receiving[kSize], receiverCount = 0;
  for (uint32_t m = foundLanes; m != 0; m &= m - 1) {
    const int i = __builtin_ctz(m);
    if (!receivesCaustics(points[i])) continue;
    receivers[receiverCount] = &points[i].surface;
    receiving[receiverCount++] = i;
    receivingLanes |= 1u << i;
  }
  Color estimates[kSize];
  terms_.caustics->irradianceAtEach(receivers, receiverCount, estimates);
  for (int k = 0; k < receiverCount; ++k) caustic[receiving[k]] = estimates[k];
  return receivingLanes;
}

[[gnu::always_inline]] inline void WhittedIntegrator::addMirrorBounce(
    const Ray& ray, const HitRecord& hit, const ShadingPoint& p, const Color& weight,
    const RayCone& cone, int lane, BouncePackets& out, RayCounters& counters) const {
  // Where nothing is transmitted, splitSpecular's weights are the material's own.
  const Color& reflectance = p.material->reflectance;
  const Color reflectContribution = weight * reflectance;
  if (!(maxComponent(reflectContribution) > scene_.settings().minContribution)) return;
  ++counters.secondary;
  out.scale[0][lane] = reflectance;
  out.contribution[0][lane] = reflectContribution;
  out.bouncing[0] |= 1u << lane;
  if (out.withCones) {
    // forEachBounce's cone of the reflected ray.
    float curvature;
    out.cones[0][lane] =
        cone.known() && bounceCurvature(hit, p.surface, cone.widthAt(hit.t), curvature)
            ? cone.reflected(hit.t, curvature)
            : RayCone{};
  }
}

[[gnu::always_inline]] inline void WhittedIntegrator::addBounces(
    const Ray& ray, const HitRecord& hit, const ShadingPoint& p, const Color& weight,
    const RayCone& cone, int depth, int lane, BouncePackets& out, RayCounters& counters) const {
  int k = 0;
  forEachBounce(
      ray, hit, p, PixelFootprint{}, depth, weight, RayDifferential{}, cone, counters,
      [&](const Vec3& origin, const Vec3& direction, const Color& rayScale,
          const Color& rayContribution, const RayDifferential&, const RayCone& onwardCone) {
        // Built here from origin and direction: a whole Ray built by the caller and
        // copied in was read back before its stores had landed (a store-forwarding
        // stall).
        out.onward[k][lane] = Ray{origin, direction};
        out.scale[k][lane] = rayScale;
        out.contribution[k][lane] = rayContribution;
        if (out.withCones) out.cones[k][lane] = onwardCone;
        out.bouncing[k] |= 1u << lane;
        ++k;
      });
}

[[gnu::always_inline]] inline void WhittedIntegrator::traceBounces(BouncePackets& bounces,
                                                                   int count, int depth,
                                                                   Color* results,
                                                                   RayCounters& counters) const {
  // Every ray's first bounce as one packet, then its second: a ray still adds its reflection
  // before its refraction. Lanes without a bounce are left out (tMax below tMin).
  for (int k = 0; k < 2 && bounces.bouncing[k] != 0; ++k) {
    for (int i = 0; i < count; ++i) {
      if (!(bounces.bouncing[k] >> i & 1u)) {
        bounces.onward[k][i].tMin = 0.0f;
        bounces.onward[k][i].tMax = -1.0f;
      }
    }
    Color arriving[BouncePackets::kSize];
    radiancePacket(bounces.onward[k].data(), count, bounces.bouncing[k], depth + 1,
                   bounces.contribution[k], bounces.withCones ? bounces.cones[k].data() : nullptr,
                   arriving, counters);
    for (uint32_t m = bounces.bouncing[k]; m != 0; m &= m - 1) {
      const int i = __builtin_ctz(m);
      results[i] += bounces.scale[k][i] * arriving[i];
    }
  }
}

void WhittedIntegrator::radiancePacket(const Ray* rays, int count, uint32_t live, int depth,
                                       const Color* weights, const RayCone* cones, Color* results,
                                       RayCounters& counters) const {
  const RayCone none;
  const auto coneOf = [&](int i) -> const RayCone& { return cones ? cones[i] : none; };
  constexpr int kSize = Scene::kPacketSize;
  // Bounces that spread out (off curved mirrors) or leave few rays cost a packet more than they
  // share: those rays go on alone.
  if (depth > 0 &&
      (simd::laneCount(live) < kMinPacketRays || !Scene::coherentDirections(rays, live))) {
    for (uint32_t m = live; m != 0; m &= m - 1) {
      const int i = __builtin_ctz(m);
      results[i] = radiance(rays[i], depth, weights[i], counters, RayDifferential{}, coneOf(i));
    }
    return;
  }
  ScratchArray<HitRecord, kSize> hits;
  bool found[kSize];
  scene_.intersect8(rays, count, hits.data(), found);

  ScratchArray<ShadingPoint, kSize> points;
  ShadingLanes lanes{};     // the points again as vector lanes; lanes without one stay zero
  uint32_t foundLanes = 0;  // bit i: rays[i] met a surface
  uint32_t litLanes = 0;    // and direct light is added there (litDirectly)
  Color direct[kSize];
  for (int i = 0; i < count; ++i) {
    direct[i] = Color(0.0f);
    if (!found[i]) continue;
    shadingPoint(rays[i], hits[i], coneOf(i), points[i]);
    lanes.set(i, points[i].surface, points[i].albedo, *points[i].material, -rays[i].direction);
    foundLanes |= 1u << i;
    litLanes |= litDirectly(points[i]) ? 1u << i : 0u;
  }
  // Direct light for all points at once (render/LightLanes.h); each point adds the lights up in
  // the order directLighting() does. A packet where no ray met a lit surface has no shadow rays
  // to trace: nearly half of the default scene's (the floor's reflections, into the sky).
  if (litLanes != 0) directLightingLanes(lanes, litLanes, count, direct, counters);
  Color caustic[kSize];
  // bit i: points[i] receives caustics, its estimate in caustic[i]
  const uint32_t receivingLanes =
      terms_.caustics ? causticEstimates(points.data(), foundLanes, caustic) : 0u;

  // The bounces: points that only reflect (no transmittance: floors, mirrors, metals) take
  // forEachBounce's reflected ray from the lanes, every lane's mirror ray computed at once
  // (render/MirrorLanes.h); points that refract go through forEachBounce.
  BouncePackets bounces(cones != nullptr);
  const bool bouncing = depth < scene_.settings().maxDepth && foundLanes != 0;
  if (bouncing) mirrorRayLanes(lanes, bounces.onward[0].data());
  for (uint32_t m = live; m != 0; m &= m - 1) {
    const int i = __builtin_ctz(m);
    if (!found[i]) {
      results[i] = escaped(rays[i], coneOf(i));
      continue;
    }
    results[i] =
        surfaceRadiance(points[i], direct[i], (receivingLanes >> i & 1u) ? &caustic[i] : nullptr);
    if (!bouncing) continue;
    if (isBlack(points[i].material->transmittance)) {
      addMirrorBounce(rays[i], hits[i], points[i], weights[i], coneOf(i), i, bounces, counters);
    } else {
      addBounces(rays[i], hits[i], points[i], weights[i], coneOf(i), depth, i, bounces, counters);
    }
  }
  traceBounces(bounces, count, depth, results, counters);
}

}  // namespace prism
