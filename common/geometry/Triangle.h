// A mesh triangle as the scalar intersectors read it: its three vertices, exactly as the mesh
// gives them (the watertight test needs neighbours to share identical vertices; edges are
// computed from them, bit for bit what precomputing them would store), plus where it came from
// so the shading normal can be interpolated after the closest hit is known.
#pragma once

#include <cstdint>

#include "math/Aabb.h"
#include "math/FloatError.h"

namespace prism {

struct Triangle {
  Vec3 v0{0.0f};
  Vec3 v1{0.0f};
  Vec3 v2{0.0f};
  uint32_t mesh = 0;
  uint32_t face = 0;

  Vec3 edge1() const { return v1 - v0; }
  Vec3 edge2() const { return v2 - v0; }

  // The point at barycentric coordinates (u, v) and the bound on its rounding per axis (pbrt-v4,
  // section 6.8.5): whatever u and v are, the sum lies in the triangle's plane up to that bound,
  // however far the ray came from.
  Vec3 pointAt(float u, float v, Vec3& error) const {
    const Vec3 p0 = (1.0f - u - v) * v0, p1 = u * v1, p2 = v * v2;
    error = gammaBound(7) * (absComponents(p0) + absComponents(p1) + absComponents(p2));
    return p0 + p1 + p2;
  }

  Aabb bounds() const {
    Aabb box;
    box.extend(v0);
    box.extend(v1);
    box.extend(v2);
    return box;
  }
};

}  // namespace prism
