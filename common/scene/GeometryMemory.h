// The memory a rank needs to hold and build a scene's geometry, and the check against a limit.
// Rank 0 runs it before it broadcasts the scene (with its own limit), and every slave again
// before it builds the scene, against its own: ranks on smaller machines refuse instead of
// running out of memory in the build (docs/reliability.md, "Limits").
#pragma once

#include <cstdint>

#include "scene/SceneDescription.h"
#include "util/MemorySize.h"

namespace prism {

// Bytes a rank needs to hold and build this scene's geometry (meshes with their BVH, the other
// primitives, cube-map faces, textures), counting the description and its wire copy (MeshBudget.h).
uint64_t geometryMemoryBytes(const SceneDescription& description);

// Bytes a rank needs to hold a texture: the description's copy, its wire copy and the scene's
// mip pyramid.
uint64_t textureMemoryBytes(const TextureDesc& texture);

// Throws ResourceLimitError when the geometry cannot fit, naming the bytes and the limit.
void checkGeometryFits(const SceneDescription& description, const MemoryLimit& limit);

}  // namespace prism
