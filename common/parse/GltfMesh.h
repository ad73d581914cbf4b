// glTF mesh primitives as Prism meshes: one MeshDesc per primitive per node that places it, in
// world space (positions by the node's world matrix, normals by its inverse transpose, the
// winding reversed where the matrix mirrors). Triangle lists are read as they are, strips and
// fans converted to lists; points and lines are skipped with a warning. Attributes read:
// POSITION, NORMAL, TEXCOORD_0 (v flipped to Prism's bottom-up convention) and COLOR_0 (linear,
// alpha dropped).
#pragma once

#include <cstdint>
#include <vector>

#include "parse/GltfAccessor.h"
#include "parse/GltfScene.h"
#include "scene/SceneDescription.h"

namespace prism {

// A primitive checked and counted before anything is allocated for it.
struct GltfPrimitivePlan {
  uint64_t mesh = 0, primitive = 0;
  int mode = 4;
  GltfAccessor position;
  std::optional<GltfAccessor> normal, texcoord, color, indices;
  std::optional<uint64_t> material;
  uint64_t vertices = 0;
  uint64_t triangles = 0;  // after strips and fans are converted
  std::string path;        // "meshes[2].primitives[0]"
};

// The triangle primitives of every mesh the scene places (points and lines skipped with a
// warning), checked: accessor types and bounds, attribute counts.
std::vector<std::vector<GltfPrimitivePlan>> planGltfMeshes(GltfDocument& doc,
                                                           const std::vector<bool>& used);

// Bytes a primitive's MeshDesc takes as read, and after it is built (MeshBudget.h).
uint64_t gltfPrimitiveBytes(const GltfPrimitivePlan& plan);

// Reads one placed primitive. noMaterial is the material index given to primitives without one.
// Throws SceneError for indices out of range and positions that are not finite.
MeshDesc readGltfPrimitive(const GltfDocument& doc, const GltfPrimitivePlan& plan,
                           const GltfMeshInstance& instance, uint32_t noMaterial);

}  // namespace prism
