// Density-estimation kernels over a disc of radius r on the receiving surface: the weight of a
// photon at distance d, normalised so the weights integrate to 1 over the disc, so that
// irradiance E = Σ Φ_p · K(d_p, r).
//   box:           K = 1 / (π r²)
//   cone (Jensen, "Realistic Image Synthesis Using Photon Mapping", §7.2, k = 1):
//                  K = 3 / (π r²) · (1 − d/r)
//   Epanechnikov:  K = 2 / (π r²) · (1 − d²/r²)
#pragma once

#include <cmath>

#include "math/Vec.h"
#include "scene/SceneDescription.h"

namespace prism {

inline float densityKernel(PhotonFilter filter, float distance2, float radius2) {
  if (!(distance2 < radius2)) return 0.0f;
  const float area = kInvPi / radius2;
  switch (filter) {
    case PhotonFilter::Box:
      return area;
    case PhotonFilter::Cone:
      return 3.0f * area * (1.0f - std::sqrt(distance2 / radius2));
    case PhotonFilter::Epanechnikov:
      return 2.0f * area * (1.0f - distance2 / radius2);
  }
  return 0.0f;
}

// The mean of the kernel over a parallelogram centred on the shading point, of edges a and b (a
// pixel's footprint), for a photon at offset q from it: the pixel's average of that photon's
// kernel. Midpoint rule on 4 × 4 points: its error changes sign with the photon's position
// relative to the points, so it adds noise, not bias.
inline float footprintMeanKernel(PhotonFilter filter, const Vec3& q, const Vec3& a, const Vec3& b,
                                 float radius2) {
  constexpr int kPoints = 4;
  float sum = 0.0f;
  for (int i = 0; i < kPoints; ++i) {
    const Vec3 row = ((i + 0.5f) / kPoints - 0.5f) * a - q;
    for (int j = 0; j < kPoints; ++j) {
      const Vec3 y = row + ((j + 0.5f) / kPoints - 0.5f) * b;
      sum += densityKernel(filter, glm::dot(y, y), radius2);
    }
  }
  return sum / (kPoints * kPoints);
}

}  // namespace prism
