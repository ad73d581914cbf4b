// Jensen's projection map: which directions leaving a point light can reach a caustic caster.
// The sphere of directions is cut into equal-area cells (uniform in cos θ and in φ); a cell is
// marked when it may see a caster's bounding sphere (or a casting plane), with a margin of the
// cell's own angular radius so the test errs on the side of marking. Photons are emitted only
// into marked cells, uniformly in solid angle, so each carries intensity × (marked solid angle)
// / (photon count): the total is the physical flux towards the casters.
#pragma once

#include <cstdint>
#include <vector>

#include "math/Vec.h"
#include "scene/Scene.h"

namespace prism {

class ProjectionMap {
 public:
  static constexpr int kDefaultRows = 256;  // cells are about 0.7° across

  ProjectionMap(const Vec3& light, const std::vector<CasterBounds>& casters,
                int rows = kDefaultRows);

  size_t cellCount() const { return static_cast<size_t>(rows_) * static_cast<size_t>(columns_); }
  size_t coveredCellCount() const { return covered_.size(); }
  bool empty() const { return covered_.empty(); }
  // Solid angle of the marked cells, steradians.
  double coveredSolidAngle() const;

  // A direction uniformly distributed over the marked cells, from three uniform numbers.
  Vec3 sample(float u0, float u1, float u2) const;
  // A direction in marked cell `cell` (0 ≤ cell < coveredCellCount()), uniformly distributed over
  // it for (u1, u2) uniform in [0, 1)².
  Vec3 sampleCell(size_t cell, float u1, float u2) const;

 private:
  int rows_, columns_;
  std::vector<uint32_t> covered_;  // indices row·columns + column of marked cells
};

}  // namespace prism
