// Whitted-style recursive ray tracing with Phong shading: ambient, Lambert diffuse, Phong
// highlights and hard shadows from point lights, plus mirror reflection and refraction with
// Fresnel and total internal reflection, to render.max_depth bounces; caustics come from a
// CausticEstimator and are added on receiving surfaces as Lambertian radiance, albedo/π · E.
#pragma once

#include "caustics/CausticEstimator.h"
#include "math/RayCone.h"
#include "math/RayDifferential.h"
#include "render/LightTerms.h"
#include "render/RayCounters.h"
#include "scene/Scene.h"

namespace prism {

struct ShadingLanes;

class WhittedIntegrator {
 public:
  // The widest footprint (its reach, over the radius) a sphere passes on to the rays it
  // reflects or refracts; wider ones end there (forEachBounce says why).
  static constexpr float kMaxFootprintReachOnSphere = 0.25f;

  explicit WhittedIntegrator(const Scene& scene, const LightTerms& terms = {})
      : scene_(scene), terms_(terms) {}

  // Radiance arriving along ray (unit direction). depth counts bounces so far; weight is the
  // product of reflection/transmission weights that scales this ray's contribution to the pixel.
  // differential is how the ray changes per pixel (Camera::pixelDifferential): the caustic
  // estimate averages over the pixel's footprint where it meets a receiver. Without one (the
  // default) the estimate is taken at the point. cone is the ray's footprint as a cone
  // (Camera::pixelCone): textures and the environment read the mip levels it asks for; without
  // one (the default) their finest levels.
  Color radiance(const Ray& ray, int depth, const Color& weight, RayCounters& counters,
                 const RayDifferential& differential = {}, const RayCone& cone = {}) const;
  // The same for up to Scene::kPacketSize camera rays at once (depth 0, weight 1, no
  // differentials; cones: each ray's, or null for none): their first hits found as one packet
  // (Scene::intersect8), the shadow rays of those hits as one packet per light (Scene::occluded8),
  // their reflection and refraction rays as packets (every pixel's first bounce, then its second)
  // while they stay coherent; direct light and mirror rays for all the packet's points at once as
  // vector lanes, the rest of the shading ray by ray. Each result is bit-identical to radiance() of
  // its ray, and counts the same rays. Only for integrators whose caustic estimate takes no
  // footprint
  // (!causticsUseFootprint()).
  void radiance8(const Ray* rays, int count, Color* results, RayCounters& counters,
                 const RayCone* cones = nullptr) const;
  // Whether radiance() uses a differential: a caustic estimate that averages over the pixel's
  // footprint (photon gathers; not the caustic map). Otherwise the tracing loop need not
  // compute them.
  bool usesDifferentials() const { return causticsUseFootprint(); }
  // Whether radiance() and radiance8() use cones: textures, or an environment filtered by the
  // footprint of the rays that escape to it, where this pass adds direct light.
  bool usesCones() const {
    return terms_.direct && (!scene_.textures().empty() || scene_.escapedRadianceFiltered());
  }
  // Whether the caustic estimate uses the footprint: radiance8 has none to give it.
  bool causticsUseFootprint() const {
    return terms_.caustics != nullptr && terms_.caustics->usesFootprint();
  }

 private:
  // Radiance along a ray that hits nothing: the environment, when this pass adds direct light,
  // filtered over the cone's spread where the ray has one.
  Color escaped(const Ray& ray, const RayCone& cone) const;
  // Radiance leaving the ray's hit towards its origin: radiance() once the hit is found.
  Color shade(const Ray& ray, const HitRecord& hit, int depth, const Color& weight,
              RayCounters& counters, const RayDifferential& differential,
              const RayCone& cone) const;
  // radiance() of the rays in `live` (bit i: rays[i]; the others have tMax below tMin), at
  // depth `depth` with path weights `weights`: their hits as one packet, their shadow rays as
  // one packet per light, their reflected and refracted rays as packets again; direct light
  // and the mirror rays of points that do not refract as vector lanes (render/LightLanes.h,
  // render/MirrorLanes.h), the rest of the shading ray by ray. Bounce packets of fewer than
  // kMinPacketRays rays, or whose directions spread (Scene::coherentDirections), go ray by ray.
  // cones: each ray's, or null for none.
  void radiancePacket(const Ray* rays, int count, uint32_t live, int depth, const Color* weights,
                      const RayCone* cones, Color* results, RayCounters& counters) const;
  static constexpr int kMinPacketRays = 3;

  // A surface point as shading reads it.
  struct ShadingPoint {
    SurfaceHit surface;
    const MaterialDesc* material = nullptr;
    Color albedo{0.0f};
  };
  // Direct light from every point light, each shadow ray traced alone.
  Color directLighting(const ShadingPoint& p, const Vec3& toViewer, RayCounters& counters) const;
  // Fills p in place (see Scene::surface); textures read over the cone's width at the hit.
  void shadingPoint(const Ray& ray, const HitRecord& hit, const RayCone& cone,
                    ShadingPoint& p) const;
  // Whether direct light (ambient, lights) is added and the surface reflects any of it.
  bool litDirectly(const ShadingPoint& p) const;

  // Everything shade() adds before it follows the surface's reflection and refraction:
  // ambient, direct light (directLight: its sum over the lights) and caustics, estimated over
  // the pixel's footprint.
  Color surfaceRadiance(const ShadingPoint& p, const Color& directLight,
                        const PixelFootprint& footprint) const;
  // The same with the caustic irradiance at p already estimated: null where p receives none
  // (receivesCaustics).
  Color surfaceRadiance(const ShadingPoint& p, const Color& directLight,
                        const Color* causticIrradiance) const;
  // Whether a caustic estimate is added at p.
  bool receivesCaustics(const ShadingPoint& p) const;

  // radiancePacket's parts, in the order it calls them: defined beside it and always inlined
  // (WhittedIntegrator.cpp says why).
  //
  // Direct light at the points of litLanes (bit i: lanes' point i), one light at a time with its
  // shadow rays as one packet: direct[i] is what directLighting() gives point i.
  inline void directLightingLanes(const ShadingLanes& lanes, uint32_t litLanes, int count,
                                  Color* direct, RayCounters& counters) const;
  // The caustic estimates of the points of foundLanes that receive one, asked all at once
  // (their lookups mostly miss the cache, and asked together their reads overlap). Returns the
  // lanes that receive one, each estimate in caustic[i].
  inline uint32_t causticEstimates(const ShadingPoint* points, uint32_t foundLanes,
                                   Color* caustic) const;
  // A packet's bounce rays, gathered lane by lane and traced as packets.
  struct BouncePackets;
  // The reflected ray of a point that transmits nothing, as forEachBounce sends it, added to
  // lane `lane` of the first bounce packet, whose ray mirrorRayLanes has already written.
  inline void addMirrorBounce(const Ray& ray, const HitRecord& hit, const ShadingPoint& p,
                              const Color& weight, const RayCone& cone, int lane,
                              BouncePackets& out, RayCounters& counters) const;
  // The reflected and refracted rays forEachBounce sends on from the hit, added to lane `lane`
  // of the first and second bounce packets.
  inline void addBounces(const Ray& ray, const HitRecord& hit, const ShadingPoint& p,
                         const Color& weight, const RayCone& cone, int depth, int lane,
                         BouncePackets& out, RayCounters& counters) const;
  // Traces the bounce packets (the first, then the second) and adds what each ray brings back,
  // scaled, to results.
  inline void traceBounces(BouncePackets& bounces, int count, int depth, Color* results,
                           RayCounters& counters) const;

  // How the surface under the footprint turns the rays it sends on (RayDifferential::Turn):
  // false where the differentials end there (forEachBounce says which surfaces).
  bool bounceTurn(const HitRecord& hit, const SurfaceHit& s, const PixelFootprint& footprint,
                  RayDifferential::Turn& turn) const;
  // The same for a cone `width` wide at the hit: the surface's curvature (0 where flat), or
  // false where the cone ends there.
  bool bounceCurvature(const HitRecord& hit, const SurfaceHit& s, float width,
                       float& curvature) const;
  // Calls send(origin, direction, weight, contribution, onward, onwardCone) for the reflected
  // and then the refracted ray the hit sends on, where there is one: weight scales the radiance
  // it brings back, contribution is the path weight it carries, onward its differential and
  // onwardCone its cone.
  template <class Send>
  void forEachBounce(const Ray& ray, const HitRecord& hit, const ShadingPoint& p,
                     const PixelFootprint& footprint, int depth, const Color& weight,
                     const RayDifferential& differential, const RayCone& cone,
                     RayCounters& counters, Send&& send) const;

  const Scene& scene_;
  LightTerms terms_;
};

}  // namespace prism
