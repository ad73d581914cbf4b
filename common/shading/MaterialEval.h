// Evaluates material properties that vary over a surface.
#pragma once

#include "math/FloorToInt.h"
#include "scene/SceneDescription.h"

namespace prism {

// Diffuse albedo at a world-space point: the solid checkerboard when the material has one
// (cells of edge `scale` alternate by the parity of floor(x/s) + floor(y/s) + floor(z/s)),
// otherwise the constant diffuse colour. Cell boundaries are shifted by a thousandth of a cell
// so a surface lying exactly on one (a floor at y = 0) does not flicker between two cells.
inline Color diffuseAlbedo(const MaterialDesc& m, const Vec3& p) {
  if (!m.checker) return m.diffuse;
  constexpr float kBoundaryShift = 1e-3f;
  const Vec3 q = p / m.checker->scale + kBoundaryShift;
  const long parity = floorToInt<long>(q.x) + floorToInt<long>(q.y) + floorToInt<long>(q.z);
  return (parity & 1) ? m.checker->colorB : m.checker->colorA;
}

}  // namespace prism
