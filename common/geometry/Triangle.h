// A mesh triangle in the layout the intersectors read: one vertex and two edges, plus where it
// came from so the shading normal can be interpolated after the closest hit is known.
#pragma once

#include <cstdint>

#include "math/Aabb.h"

namespace prism {

struct Triangle {
  Vec3 v0;
  Vec3 e1;  // v1 − v0
  Vec3 e2;  // v2 − v0
  uint32_t mesh = 0;
  uint32_t face = 0;

  Aabb bounds() const {
    Aabb box;
    box.extend(v0);
    box.extend(v0 + e1);
    box.extend(v0 + e2);
    return box;
  }
};

}  // namespace prism
