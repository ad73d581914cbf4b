// Whitted-style recursive ray tracing with Phong shading: ambient, Lambert diffuse, Phong
// highlights and hard shadows from point lights, plus mirror reflection and refraction with
// Fresnel and total internal reflection, to render.max_depth bounces; caustics come from a
// CausticEstimator and are added on receiving surfaces as Lambertian radiance, albedo/π · E.
#pragma once

#include "caustics/CausticEstimator.h"
#include "math/RayDifferential.h"
#include "render/LightTerms.h"
#include "render/RayCounters.h"
#include "scene/Scene.h"

namespace prism {

class WhittedIntegrator {
 public:
  explicit WhittedIntegrator(const Scene& scene, const LightTerms& terms = {})
      : scene_(scene), terms_(terms) {}

  // Radiance arriving along ray (unit direction). depth counts bounces so far; weight is the
  // product of reflection/transmission weights that scales this ray's contribution to the pixel.
  // differential is how the ray changes per pixel (Camera::pixelDifferential): the caustic
  // estimate averages over the pixel's footprint where it meets a receiver. Without one (the
  // default) the estimate is taken at the point.
  Color radiance(const Ray& ray, int depth, const Color& weight, RayCounters& counters,
                 const RayDifferential& differential = {}) const;
  // The same for up to Scene::kPacketSize camera rays at once (depth 0, weight 1, no
  // differential): their first hits found as one packet (Scene::intersect8), everything after
  // ray by ray. Each result is bit-identical to radiance() of its ray. Only for integrators
  // that use no differentials.
  void radiance8(const Ray* rays, int count, Color* results, RayCounters& counters) const;
  // Whether radiance() uses a differential: only a caustic estimate that averages over the
  // pixel's footprint does (photon gathers; not the caustic map), so otherwise the tracing loop
  // need not compute them.
  bool usesDifferentials() const {
    return terms_.caustics != nullptr && terms_.caustics->usesFootprint();
  }

 private:
  // Radiance along a ray that hits nothing: the environment, when this pass adds direct light.
  Color escaped(const Ray& ray) const;
  // Radiance leaving the ray's hit towards its origin: radiance() once the hit is found.
  Color shade(const Ray& ray, const HitRecord& hit, int depth, const Color& weight,
              RayCounters& counters, const RayDifferential& differential) const;
  Color directLighting(const SurfaceHit& s, const MaterialDesc& m, const Color& albedo,
                       const Vec3& toViewer, RayCounters& counters) const;

  const Scene& scene_;
  LightTerms terms_;
};

}  // namespace prism
