// Mirror reflection, Snell refraction and Fresnel reflectance for smooth dielectrics.
#pragma once

#include <optional>

#include "math/Vec.h"

namespace prism {

// Reflects incident direction d about unit normal n.
inline Vec3 reflect(const Vec3& d, const Vec3& n) {
  return d - 2.0f * glm::dot(d, n) * n;
}

// Refracts unit direction d at a surface with unit normal n facing against d, going from index
// n1 to n2 (eta = n1 / n2). Returns nothing on total internal reflection.
inline std::optional<Vec3> refract(const Vec3& d, const Vec3& n, float eta) {
  const float cosIncident = -glm::dot(d, n);
  const float sin2Transmitted = eta * eta * std::max(0.0f, 1.0f - cosIncident * cosIncident);
  if (sin2Transmitted > 1.0f) return std::nullopt;
  const float cosTransmitted = std::sqrt(1.0f - sin2Transmitted);
  return glm::normalize(eta * d + (eta * cosIncident - cosTransmitted) * n);
}

// Unpolarised Fresnel reflectance of a smooth dielectric interface (the mean of the s and p
// amplitudes squared, Hecht, "Optics", §4.6). cosIncident > 0; eta = n1 / n2. Returns 1 beyond
// the critical angle (total internal reflection).
inline float fresnelDielectric(float cosIncident, float eta) {
  cosIncident = std::clamp(cosIncident, 0.0f, 1.0f);
  const float sin2Transmitted = eta * eta * (1.0f - cosIncident * cosIncident);
  if (sin2Transmitted >= 1.0f) return 1.0f;
  const float cosTransmitted = std::sqrt(1.0f - sin2Transmitted);
  // With n1 = eta·n2: rs = (eta·cosI − cosT) / (eta·cosI + cosT), rp = (cosI − eta·cosT) / (…).
  const float rs = (eta * cosIncident - cosTransmitted) / (eta * cosIncident + cosTransmitted);
  const float rp = (cosIncident - eta * cosTransmitted) / (cosIncident + eta * cosTransmitted);
  return 0.5f * (rs * rs + rp * rp);
}

}  // namespace prism
