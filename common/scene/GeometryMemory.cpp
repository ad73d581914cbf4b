#include "scene/GeometryMemory.h"

#include <string>

#include "accel/PrimitiveRef.h"
#include "image/MipPyramid.h"
#include "scene/MeshBudget.h"

namespace prism {

// kBytesPerOtherPrimitive counts a shape's copy in the Scene as at most this: a bigger kind
// needs the estimate raised (scene/MeshBudget.h).
#define PRISM_SHAPE_FITS_ESTIMATE(Shape, plural) \
  static_assert(sizeof(Shape) <= 96, #Shape " is larger than scene/MeshBudget.h counts");
PRISM_SHAPE_KINDS(PRISM_SHAPE_FITS_ESTIMATE)
#undef PRISM_SHAPE_FITS_ESTIMATE

namespace {

// The entries a kind's shapes take in the BVH (a slanted cone enters in parts).
template <class Descs>
uint64_t bvhPartsOf(const Descs& descs) {
  uint64_t parts = 0;
  for (const auto& desc : descs) parts += partCountForBvh(desc.shape());
  return parts;
}

// What an image a scene reads through mip levels (a cube face, a texture) costs: the
// description's copy, its wire copy and the scene's with its mip levels: as 3 bytes, 3 bytes and
// packed 4-byte texels (while the levels above the finest are built, a float copy of the second
// level) where it is kept as bytes, else as floats.
uint64_t mippedImageBytes(int width, int height, bool keptAsBytes) {
  const uint64_t texels = static_cast<uint64_t>(width) * static_cast<uint64_t>(height);
  const uint64_t pyramid = mipLevelsTexels(width, height);
  return keptAsBytes ? saturatingAdd(saturatingAdd(saturatingMultiply(2 * texels, 3),
                                                   saturatingMultiply(pyramid, 4)),
                                     saturatingMultiply(texels / 4, sizeof(Color)))
                     : saturatingMultiply(2 * texels + pyramid, sizeof(Color));
}

// A mesh's texture coordinates, vertex colours and face materials: in the description and in
// the scene's shading data.
uint64_t meshAttributeBytes(const MeshDesc& m) {
  return 2 * (m.uvs.size() * sizeof(Vec2) + m.colors.size() * sizeof(Color) +
              m.faceMaterials.size() * sizeof(MaterialId));
}

}  // namespace

uint64_t textureMemoryBytes(const TextureDesc& t) {
  return mippedImageBytes(t.width(), t.height(), t.keptAsBytes());
}

uint64_t geometryMemoryBytes(const SceneDescription& d) {
  uint64_t bytes = 0;
  for (const MeshDesc& m : d.meshes) {
    bytes = saturatingAdd(bytes, meshBuildBytes(m.triangleCount(), m.positions.size()));
    bytes = saturatingAdd(bytes, meshAttributeBytes(m));
  }
  for (const TextureDesc& t : d.textures) bytes = saturatingAdd(bytes, textureMemoryBytes(t));
  // Each shape's parts in the BVH (a slanted cone enters in parts) cost what a sphere does.
  uint64_t primitives = d.planes.size();
  forEachShapeList(d, [&](const auto& descs) { primitives += bvhPartsOf(descs); });
  bytes = saturatingAdd(bytes, saturatingMultiply(primitives, kBytesPerOtherPrimitive));
  if (d.environment) {
    const CubeMapDesc& cube = *d.environment;
    for (int f = 0; f < 6; ++f) {
      const int width = cube.faceWidth(f), height = cube.faceHeight(f);
      const uint64_t faceBytes = mippedImageBytes(width, height, cube.keptAsBytes());
      bytes = saturatingAdd(bytes, faceBytes);
    }
  }
  return bytes;
}

void checkGeometryFits(const SceneDescription& d, const MemoryLimit& limit) {
  // The BVH's entries number each kind's primitives in PrimitiveRef's index bits.
  if (d.triangleCount() > kMaxTriangles) {
    throw ResourceLimitError("the scene's " + std::to_string(d.triangleCount()) +
                             " triangles are more than a BVH numbers (at most " +
                             std::to_string(kMaxTriangles) + "): split the scene");
  }
  forEachShapeList(d, [](const auto& descs) {
    const uint64_t parts = bvhPartsOf(descs);
    if (parts > PrimitiveRef::kMaxIndex) {
      throw ResourceLimitError("the scene's " + std::to_string(parts) + " BVH parts of " +
                               std::string(descs.front().kName) +
                               "s are more than a BVH numbers (at most " +
                               std::to_string(PrimitiveRef::kMaxIndex) + ")");
    }
  });
  const uint64_t needed = geometryMemoryBytes(d);
  if (needed > limit.bytes) {
    throw ResourceLimitError(
        memoryRefusal("the scene's geometry (" + std::to_string(d.triangleCount()) + " triangles)",
                      needed, limit, "simplify the meshes"));
  }
}

}  // namespace prism
