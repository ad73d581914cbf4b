// A mesh triangle as the scalar intersectors read it: its three vertices, exactly as the mesh
// gives them (the watertight test needs neighbours to share identical vertices; edges are
// computed from them, bit for bit what precomputing them would store), plus where it came from
// so the shading normal can be interpolated after the closest hit is known.
#pragma once

#include <cstdint>

#include "math/Aabb.h"

namespace prism {

struct Triangle {
  Vec3 v0{0.0f};
  Vec3 v1{0.0f};
  Vec3 v2{0.0f};
  uint32_t mesh = 0;
  uint32_t face = 0;

  Vec3 edge1() const { return v1 - v0; }
  Vec3 edge2() const { return v2 - v0; }

  Aabb bounds() const {
    Aabb box;
    box.extend(v0);
    box.extend(v1);
    box.extend(v2);
    return box;
  }
};

}  // namespace prism
