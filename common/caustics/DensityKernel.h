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

// The share of a kernel of radius r that lies on the near side of a line at signed distance
// t·r from its centre (t ≥ 1: all of it, t ≤ −1: none): the cumulative distribution of the
// kernel's marginal along any direction, in closed form (r = 1, s = √(1 − t²)):
//   box:           ½ + (t·s + asin t) / π
//   cone:          ½ ± (2|t|·s + asin|t| − |t|³·arsech|t|) / π
//   Epanechnikov:  ½ + (t·(5 − 2t²)·s + 3·asin t) / (3π)
inline float kernelShareBelow(PhotonFilter filter, float t) {
  if (!(t < 1.0f)) return 1.0f;
  if (!(t > -1.0f)) return 0.0f;
  const float s = std::sqrt(1.0f - t * t);
  float half = 0.0f;  // the share between the centre and the line, signed as t
  switch (filter) {
    case PhotonFilter::Box:
      half = (t * s + std::asin(t)) * kInvPi;
      break;
    case PhotonFilter::Cone: {
      const float a = std::fabs(t);
      const float arsech = a > 0.0f ? std::log((1.0f + s) / a) : 0.0f;
      half = std::copysign((2.0f * a * s + std::asin(a) - a * a * a * arsech) * kInvPi, t);
      break;
    }
    case PhotonFilter::Epanechnikov:
      half = (t * (5.0f - 2.0f * t * t) * s + 3.0f * std::asin(t)) * (kInvPi / 3.0f);
      break;
  }
  return 0.5f + half;
}

// The share of a photon's kernel (radius r) that a pixel's footprint holds, for a photon narrower
// than the footprint at dual coordinates (u, v) (PixelFootprint::Test: the footprint is
// |u|, |v| ≤ ½, its edges 1/|dualA| and 1/|dualB| apart): the product of the shares between each
// pair of opposite edges. The product is the kernel's share exactly where the disc crosses one
// edge, and where it crosses two it stands for the kernel made of its two marginals; either way
// the shares of a row of tiling footprints sum to 1, so a photon counts its whole power once in
// the pixels around it, and a photon near an edge counts in both pixels in proportion rather
// than wholly in the one its centre falls in (whose count jumped by a photon as the photon
// crossed the edge: the noise of the count of photons in a footprint).
inline float kernelShareOfFootprint(PhotonFilter filter, float u, float v, float dualALength,
                                    float dualBLength, float radius) {
  const auto between = [&](float w, float dualLength) {
    const float reach = radius * dualLength;   // the kernel's radius, in units of w
    const float inside = 0.5f - std::fabs(w);  // to the nearer edge (below 0: beyond it)
    if (inside >= reach) return 1.0f;          // wholly between the edges (a point inside, too)
    if (inside <= -reach) return 0.0f;         // wholly beyond the nearer edge
    return kernelShareBelow(filter, (0.5f - w) / reach) -
           kernelShareBelow(filter, (-0.5f - w) / reach);
  };
  return between(u, dualALength) * between(v, dualBLength);
}

}  // namespace prism
