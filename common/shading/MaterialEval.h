// Evaluates material properties that vary over a surface.
#pragma once

#include <cmath>
#include <vector>

#include "geometry/HitRecord.h"
#include "math/FloorToInt.h"
#include "scene/SceneDescription.h"
#include "scene/Texture.h"

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

// Where a texture map reads the texture for surface coordinates uv (TextureMap's transform).
inline Vec2 mappedCoordinates(const TextureMap& map, Vec2 uv) {
  Vec2 q = map.scale * uv;
  if (map.rotation != 0.0f) {
    const float c = std::cos(map.rotation), s = std::sin(map.rotation);
    q = Vec2(c * q.x - s * q.y, s * q.x + c * q.y);
  }
  return q + map.offset;
}

// The same at a surface hit, with what the surface adds: the material's texture (where it has
// one and the surface has texture coordinates) read over the footprint of a ray cone
// `coneWidth` wide at the hit (0: the texture's finest level), arriving along unit direction d,
// and the mesh's vertex colour.
inline Color diffuseAlbedo(const MaterialDesc& m, const SurfaceHit& s,
                           const std::vector<Texture>& textures, const Vec3& d, float coneWidth) {
  Color albedo = diffuseAlbedo(m, s.position) * s.vertexColor;
  if (m.diffuseMap && s.uvPerWorld >= 0.0f) {
    const TextureMap& map = *m.diffuseMap;
    // The cone's width across the surface (wider by 1/cos where it meets it obliquely), in
    // texture units; the map's scale stretches it too.
    const float cosine = std::fabs(glm::dot(d, s.geometricNormal));
    const float across = coneWidth * s.uvPerWorld *
                         std::max(std::fabs(map.scale.x), std::fabs(map.scale.y)) /
                         std::max(cosine, 1e-3f);
    albedo *= textures[map.texture].lookup(mappedCoordinates(map, s.uv), across);
  }
  return albedo;
}

}  // namespace prism
