// What traversal records about the closest hit so far, and the full surface description computed
// once for the final hit only (normals and materials are not needed for rejected candidates).
#pragma once

#include <cstdint>

#include "geometry/MaterialId.h"
#include "math/RayOffset.h"
#include "math/Vec.h"

namespace prism {

// Bits of SurfaceHit::caustic.
inline constexpr uint8_t kCastsCaustics = 1;     // photons continue specularly from it
inline constexpr uint8_t kReceivesCaustics = 2;  // photons are stored on it

struct HitRecord {
  float t = 0.0f;
  uint32_t primitive = 0;  // a PrimitiveRef (see accel/PrimitiveRef.h)
  float u = 0.0f;          // barycentric coordinates for triangles
  float v = 0.0f;
};

struct SurfaceHit {
  Vec3 position{0.0f};
  // How far rays leaving it start along the normal: beyond the rounding of position
  // (math/RayOffset.h, Scene::surface).
  float leavingDistance = 0.0f;
  Vec3 geometricNormal{0.0f};  // unit, facing the incoming ray
  Vec3 shadingNormal{0.0f};    // unit, interpolated for smooth meshes, same side as geometricNormal
  bool frontFace = true;       // the ray arrived from the side the surface normal points to
  MaterialId material = 0;
  uint8_t caustic = 0;  // kCastsCaustics | kReceivesCaustics, resolved per object
  // Texture coordinates where the surface has them (a mesh with uvs), interpolated
  // barycentrically, and how many texture-space units one world unit spans on the triangle
  // (sqrt of their areas' ratio): what a ray cone's width turns into a mip level. Negative: the
  // surface has no uvs (uv is then not written).
  Vec2 uv{0.0f};
  float uvPerWorld = -1.0f;
  Color vertexColor{1.0f};  // the mesh's vertex colours interpolated; 1 where it has none

  // Where a ray leaving this point in `direction` starts: just off the surface, to its side.
  Vec3 rayOrigin(const Vec3& direction) const {
    return leavingOrigin(position, geometricNormal, leavingDistance, direction);
  }
};

}  // namespace prism
