#include "render/WhittedIntegrator.h"

#include "math/RayOffset.h"
#include "scene/PrimitiveRef.h"
#include "shading/LightFalloff.h"
#include "shading/MaterialEval.h"
#include "shading/Optics.h"
#include "shading/SpecularSplit.h"

namespace prism {

Color WhittedIntegrator::directLighting(const SurfaceHit& s, const MaterialDesc& m,
                                        const Color& albedo, const Vec3& toViewer,
                                        RayCounters& counters) const {
  Color result(0.0f);
  const bool hasSpecular = !isBlack(m.specular);
  for (const PointLightDesc& light : scene_.lights()) {
    const Vec3 toLight = light.position - s.position;
    const float distance = glm::length(toLight);
    if (!(distance > 0.0f)) continue;
    const Vec3 l = toLight / distance;
    // A light below the geometric surface cannot reach it, whatever the shading normal says.
    if (glm::dot(s.geometricNormal, l) <= 0.0f) continue;
    const float cosTheta = glm::dot(s.shadingNormal, l);
    if (cosTheta <= 0.0f) continue;

    Ray shadow;
    shadow.origin = s.rayOrigin(l);
    shadow.direction = l;
    shadow.tMax = shadowRayLength(glm::length(light.position - shadow.origin));
    ++counters.shadow;
    if (scene_.occluded(shadow)) continue;

    // Irradiance factor I·att(d); times albedo/π·cosθ it is Lambertian radiance in W/(m²·sr).
    const Color lightAtSurface = light.intensity * attenuationFactor(light.attenuation, distance);
    Color reflected = albedo * (kInvPi * cosTheta);
    if (hasSpecular) {
      const float rv = glm::dot(reflect(-l, s.shadingNormal), toViewer);
      if (rv > 0.0f) reflected += m.specular * std::pow(rv, m.shininess);
    }
    result += lightAtSurface * reflected;
  }
  return result;
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

void WhittedIntegrator::radiance8(const Ray* rays, int count, Color* results,
                                  RayCounters& counters) const {
  HitRecord hits[Scene::kPacketSize];
  bool found[Scene::kPacketSize];
  scene_.intersect8(rays, count, hits, found);
  for (int i = 0; i < count; ++i) {
    if (found[i]) {
      results[i] = shade(rays[i], hits[i], 0, Color(1.0f), counters, {});
    } else {
      results[i] = escaped(rays[i]);
    }
  }
}

Color WhittedIntegrator::escaped(const Ray& ray) const {
  return terms_.direct ? scene_.escapedRadiance(ray.direction) : Color(0.0f);
}

Color WhittedIntegrator::shade(const Ray& ray, const HitRecord& hit, int depth, const Color& weight,
                               RayCounters& counters, const RayDifferential& differential) const {
  const SurfaceHit s = scene_.surface(ray, hit);
  const MaterialDesc& m = scene_.materials()[s.material];
  const Color albedo = diffuseAlbedo(m, s.position);
  const Vec3 toViewer = -ray.direction;

  Color result(0.0f);
  if (terms_.direct) {
    result = m.ambient * scene_.ambientLight();
    if (!isBlack(albedo) || !isBlack(m.specular)) {
      result += directLighting(s, m, albedo, toViewer, counters);
    }
  }
  const PixelFootprint footprint = differential.footprint(ray.direction, hit.t, s.geometricNormal);
  if (terms_.caustics && (s.caustic & kReceivesCaustics) && !isBlack(albedo)) {
    result += albedo * kInvPi * terms_.caustics->irradianceAt(s, footprint);
  }

  const RenderSettings& settings = scene_.settings();
  if (depth >= settings.maxDepth) return result;
  // Planes, flat triangles and spheres pass the pixel's footprint on, turned by their curvature;
  // other curved surfaces (cones, smooth-shaded meshes) end it, and estimates past them are
  // taken at the point.
  const PrimitiveKind kind = PrimitiveRef::kind(hit.primitive);
  bool turnKnown = kind == PrimitiveKind::Plane ||
                   (kind == PrimitiveKind::Triangle && s.shadingNormal == s.geometricNormal);
  RayDifferential::Turn turn;
  if (kind == PrimitiveKind::Sphere && footprint.valid) {
    const float radius = scene_.spheres()[PrimitiveRef::index(hit.primitive)].radius;
    turn = RayDifferential::sphereTurn(footprint, (s.frontFace ? 1.0f : -1.0f) / radius);
    turnKnown = true;
  }

  const auto [reflectWeight, transmitWeight, refracted] = splitSpecular(m, s, ray.direction);

  const Color reflectContribution = weight * reflectWeight;
  if (maxComponent(reflectContribution) > settings.minContribution) {
    const Vec3 direction = reflectedDirection(s, ray.direction);
    Ray reflected{s.rayOrigin(direction), direction};
    ++counters.secondary;
    const RayDifferential onward =
        turnKnown ? differential.reflected(footprint, ray.direction, s.geometricNormal, turn)
                  : RayDifferential{};
    result += reflectWeight * radiance(reflected, depth + 1, reflectContribution, counters, onward);
  }

  const Color transmitContribution = weight * transmitWeight;
  if (refracted && maxComponent(transmitContribution) > settings.minContribution) {
    Ray transmitted{s.rayOrigin(*refracted), *refracted};
    ++counters.secondary;
    const float eta = s.frontFace ? 1.0f / m.ior : m.ior;
    const RayDifferential onward =
        turnKnown ? differential.refracted(footprint, ray.direction, s.shadingNormal, turn,
                                           *refracted, eta)
                  : RayDifferential{};
    result +=
        transmitWeight * radiance(transmitted, depth + 1, transmitContribution, counters, onward);
  }
  return result;
}

}  // namespace prism
