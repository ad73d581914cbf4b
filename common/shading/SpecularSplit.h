// How a surface divides light arriving along a direction between mirror reflection and
// refraction: the material's reflectance and transmittance, with Fresnel moving part of the
// transmittance into reflection and total internal reflection moving all of it. Eye rays
// (WhittedIntegrator) and photons (PhotonTracer) use the same split, so the two agree.
#pragma once

#include <optional>

#include "geometry/HitRecord.h"
#include "shading/Optics.h"

namespace prism {

struct SpecularSplit {
  Color reflectWeight{0.0f};
  Color transmitWeight{0.0f};
  std::optional<Vec3> refracted;  // set when transmitWeight is not black
};

inline bool isBlack(const Color& c) {
  return c.x <= 0.0f && c.y <= 0.0f && c.z <= 0.0f;
}

inline SpecularSplit splitSpecular(const MaterialDesc& m, const SurfaceHit& s,
                                   const Vec3& direction) {
  SpecularSplit split{m.reflectance, m.transmittance, std::nullopt};
  if (isBlack(split.transmitWeight)) return split;
  const float eta = s.frontFace ? 1.0f / m.ior : m.ior;
  split.refracted = refract(direction, s.shadingNormal, eta);
  if (!split.refracted) {
    split.reflectWeight += split.transmitWeight;
    split.transmitWeight = Color(0.0f);
  } else if (m.fresnel) {
    const float f = fresnelDielectric(glm::dot(-direction, s.shadingNormal), eta);
    split.reflectWeight += f * split.transmitWeight;
    split.transmitWeight *= 1.0f - f;
  }
  return split;
}

// Mirror direction about the shading normal; a smooth normal can send it below the true
// surface, and then it is mirrored about the geometry instead.
inline Vec3 reflectedDirection(const SurfaceHit& s, const Vec3& direction) {
  const Vec3 r = reflect(direction, s.shadingNormal);
  return glm::dot(r, s.geometricNormal) > 0.0f ? r : reflect(direction, s.geometricNormal);
}

}  // namespace prism
