// How a ray moves when its pixel sample moves by one pixel in x or in y (Igehy 1999, "ray
// differentials"), carried along a traced path so that at a hit it gives the pixel's footprint
// on the surface: the parallelogram whose average the pixel measures. A density estimate (a
// photon gather) can then give a pixel the average over its footprint, not the value at one
// point: a focus narrower than a pixel is counted once, in the pixel it falls in. Reflection
// and refraction at planes, flat triangles and spheres pass the differentials on (a sphere's
// curvature turns them: seen through a glass ball the footprint is the magnified one, unless the
// footprint is too wide for the ball: WhittedIntegrator::kMaxFootprintReachOnSphere); other
// curved surfaces end them, and the estimate past them is taken at the point.
#pragma once

#include <cmath>

#include "math/Vec.h"

namespace prism {

// The pixel's footprint on a surface: the parallelogram centre ± a/2 ± b/2 (a and b are the hit
// point's changes per pixel in x and y). An invalid footprint asks for the estimate at a point.
// With several samples a pixel, a sample stands for its stratum of the pixel: its cell.
struct PixelFootprint {
  bool valid = false;
  Vec3 a{0.0f}, b{0.0f};
  // The centre of the sample's cell less the sample's image-plane point, and the cell's size, in
  // pixels (0 and 1 × 1: the pixel about the sample). The cells of a pixel's strata tile it, so
  // a focus narrower than a pixel is counted once in it; a footprint of the whole pixel about
  // each jittered sample counted it in the samples' neighbours too (a tent one pixel wider than
  // the pixel, the same in every progressive pass: docs/accuracy.md).
  Vec2 toCellCentre{0.0f};
  Vec2 cell{1.0f};

  // The cell's centre less the hit point, to first order.
  Vec3 offset() const { return toCellCentre.x * a + toCellCentre.y * b; }
  // The sample's cell as a footprint of its own, about the hit point plus offset().
  PixelFootprint sampleCell() const { return {valid, cell.x * a, cell.y * b}; }

  float area() const { return glm::length(glm::cross(a, b)); }
  // No point of the parallelogram is further than this from its centre.
  float reach() const { return 0.5f * (glm::length(a) + glm::length(b)); }
  // Answers "does the point offset by q from the centre lie in the parallelogram, within half
  // its reach of its plane (n: the surface's unit normal)?" with three dot products: q's
  // coordinates along a and b come from the dual basis, found once. grownBy(m) asks the same of
  // the parallelogram grown by m on every side (its edges moved out by m, perpendicular to them).
  struct Test {
    Vec3 dualA{0.0f}, dualB{0.0f}, normal{0.0f};
    float slab = -1.0f;                  // no point passes a test of a degenerate parallelogram
    float limitA = 0.5f, limitB = 0.5f;  // the half-widths in the dual coordinates
    bool contains(const Vec3& q) const {
      return std::fabs(glm::dot(q, normal)) <= slab && std::fabs(glm::dot(q, dualA)) <= limitA &&
             std::fabs(glm::dot(q, dualB)) <= limitB;
    }
    // An edge u = ½ lies 1/|dualA| from the line u = 0 per unit of u.
    Test grownBy(float margin) const {
      Test grown = *this;
      grown.limitA = limitA + margin * glm::length(dualA);
      grown.limitB = limitB + margin * glm::length(dualB);
      return grown;
    }
  };
  Test test(const Vec3& n) const {
    const float aa = glm::dot(a, a), ab = glm::dot(a, b), bb = glm::dot(b, b);
    const float det = aa * bb - ab * ab;
    if (!(det > 0.0f)) return {};
    return {(bb * a - ab * b) / det, (aa * b - ab * a) / det, n, 0.5f * reach()};
  }
};

struct RayDifferential {
  bool valid = false;
  Vec3 dOdx{0.0f}, dOdy{0.0f};          // the origin's change per pixel
  Vec3 dDdx{0.0f}, dDdy{0.0f};          // the unit direction's change per pixel
  Vec2 toCellCentre{0.0f}, cell{1.0f};  // as PixelFootprint's, carried along the path

  // The footprint where a ray of unit direction d meets, at distance t, a surface of unit normal
  // n. At grazing angles (|cos| below 0.05) it would grow without bound: none then.
  PixelFootprint footprint(const Vec3& d, float t, const Vec3& n) const {
    if (!valid) return {};
    const float cosine = glm::dot(d, n);
    if (!(std::fabs(cosine) >= 0.05f)) return {};
    return {true, transfer(dOdx, dDdx, d, t, n, cosine), transfer(dOdy, dDdy, d, t, n, cosine),
            toCellCentre, cell};
  }

  // How the surface's unit normal n (facing the ray) turns per pixel where the footprint lies:
  // 0 on a flat surface, ±a/R and ±b/R on a sphere of radius R (curvature = ±1/R, + where n
  // points out of the sphere).
  struct Turn {
    Vec3 dndx{0.0f}, dndy{0.0f};
  };
  static Turn sphereTurn(const PixelFootprint& f, float curvature) {
    return {curvature * f.a, curvature * f.b};
  }

  // The differentials of the ray that leaves the footprint reflected (mirror direction r of unit
  // incident direction d about n).
  RayDifferential reflected(const PixelFootprint& f, const Vec3& d, const Vec3& n,
                            const Turn& turn) const {
    if (!f.valid) return {};
    const auto turned = [&](const Vec3& dD, const Vec3& dn) {
      const float dDn = glm::dot(dD, n) + glm::dot(d, dn);
      return dD - 2.0f * (glm::dot(d, n) * dn + dDn * n);
    };
    return {true,           f.a,   f.b, turned(dDdx, turn.dndx), turned(dDdy, turn.dndy),
            f.toCellCentre, f.cell};
  }

  // The same for the ray refracted into direction t (unit, from refract(d, n, eta)): Igehy's
  // t = eta·d + mu·n with mu = eta·cos_i − cos_t, differentiated.
  RayDifferential refracted(const PixelFootprint& f, const Vec3& d, const Vec3& n, const Turn& turn,
                            const Vec3& t, float eta) const {
    if (!f.valid) return {};
    const float cosI = -glm::dot(d, n), cosT = -glm::dot(t, n);
    if (!(cosT > 1e-4f)) return {};
    const float mu = eta * cosI - cosT;
    const auto turned = [&](const Vec3& dD, const Vec3& dn) {
      const float dCosI = -(glm::dot(dD, n) + glm::dot(d, dn));
      const float dMu = (eta - eta * eta * cosI / cosT) * dCosI;
      return eta * dD + mu * dn + dMu * n;
    };
    return {true,           f.a,   f.b, turned(dDdx, turn.dndx), turned(dDdy, turn.dndy),
            f.toCellCentre, f.cell};
  }

 private:
  // The hit point P = O + t·d stays on the plane: dP = dO + t·dD + dt·d with dP·n = 0.
  static Vec3 transfer(const Vec3& dO, const Vec3& dD, const Vec3& d, float t, const Vec3& n,
                       float cosine) {
    const Vec3 moved = dO + t * dD;
    return moved - (glm::dot(moved, n) / cosine) * d;
  }
};

}  // namespace prism
