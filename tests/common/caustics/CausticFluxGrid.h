// Caustic flux per cell of a rectangle on a receiving surface, measured two ways so caustic
// mapping can be scored against photon mapping without any image or kernel in between:
//   photons:   the power of the caustic photons that landed in each cell (a histogram: no
//              density kernel, so no blur bias; noise falls as 1/√photons per cell);
//   estimator: the estimator's irradiance integrated over each cell (midpoint rule on a
//              sub-grid of lookups).
// Used by the failure-case tests and by tests/bench/caustic_map_study.cpp.
#pragma once

#include <cmath>
#include <vector>

#include "caustics/CausticEstimator.h"
#include "caustics/Photon.h"

namespace prism::test {

struct FluxGrid {
  Vec3 corner{0.0f};     // one corner of the rectangle
  Vec3 u{1, 0, 0};       // the edge along which cells are counted first
  Vec3 v{0, 0, 1};       // the other edge, perpendicular to u
  Vec3 facing{0, 1, 0};  // unit normal of the receiving side
  int cellsU = 1, cellsV = 1;

  size_t cells() const { return static_cast<size_t>(cellsU) * cellsV; }
  double cellArea() const { return glm::length(u) * glm::length(v) / static_cast<double>(cells()); }
  Vec3 at(float su, float sv) const { return corner + su * u + sv * v; }
};

// A horizontal rectangle [x0, x1] × [z0, z1] at height y, receiving from above, in cells of
// about `cell` on a side.
inline FluxGrid horizontalGrid(float y, float x0, float x1, float z0, float z1, float cell) {
  FluxGrid g;
  g.corner = {x0, y, z0};
  g.u = {x1 - x0, 0, 0};
  g.v = {0, 0, z1 - z0};
  g.cellsU = std::max(1, static_cast<int>(std::lround((x1 - x0) / cell)));
  g.cellsV = std::max(1, static_cast<int>(std::lround((z1 - z0) / cell)));
  return g;
}

// Power (green channel, W) of the photons that arrived on the grid's receiving side within
// `tolerance` of its plane, per cell.
inline std::vector<double> photonCellFlux(const FluxGrid& g, const std::vector<Photon>& photons,
                                          float tolerance = 1e-3f) {
  std::vector<double> flux(g.cells(), 0.0);
  const Vec3 du = g.u / glm::dot(g.u, g.u), dv = g.v / glm::dot(g.v, g.v);
  for (const Photon& p : photons) {
    const Vec3 r = p.position - g.corner;
    if (std::abs(glm::dot(r, g.facing)) > tolerance) continue;
    if (glm::dot(p.directionVector(), g.facing) >= 0.0f) continue;  // arrived from behind
    const float su = glm::dot(r, du), sv = glm::dot(r, dv);
    if (su < 0.0f || sv < 0.0f || su >= 1.0f || sv >= 1.0f) continue;
    const int i = std::min(g.cellsU - 1, static_cast<int>(su * g.cellsU));
    const int j = std::min(g.cellsV - 1, static_cast<int>(sv * g.cellsV));
    flux[static_cast<size_t>(j) * g.cellsU + i] += p.power.y;
  }
  return flux;
}

// ∫ E dA per cell (green channel, W) from `sub`² lookups per cell.
inline std::vector<double> estimatorCellFlux(const FluxGrid& g, const CausticEstimator& estimator,
                                             int sub = 4) {
  std::vector<double> flux(g.cells(), 0.0);
  const double area = g.cellArea() / (sub * sub);
  for (int j = 0; j < g.cellsV; ++j) {
    for (int i = 0; i < g.cellsU; ++i) {
      double sum = 0.0;
      for (int b = 0; b < sub; ++b) {
        for (int a = 0; a < sub; ++a) {
          const float su = (i + (a + 0.5f) / sub) / g.cellsU;
          const float sv = (j + (b + 0.5f) / sub) / g.cellsV;
          sum += estimator.irradiance(g.at(su, sv), g.facing).y;
        }
      }
      flux[static_cast<size_t>(j) * g.cellsU + i] = sum * area;
    }
  }
  return flux;
}

inline double totalFlux(const std::vector<double>& cells) {
  double sum = 0.0;
  for (const double c : cells) sum += c;
  return sum;
}

// Σ|a − reference| / Σ reference: the share of the reference caustic's flux that is missing,
// misplaced or invented, cell by cell.
inline double relativeL1(const std::vector<double>& a, const std::vector<double>& reference) {
  double diff = 0.0;
  for (size_t i = 0; i < a.size(); ++i) diff += std::abs(a[i] - reference[i]);
  return diff / totalFlux(reference);
}

}  // namespace prism::test
