#include "scene/GeometryMemory.h"

#include <string>

#include "geometry/ConeSegments.h"
#include "image/MipPyramid.h"
#include "scene/MeshBudget.h"

namespace prism {

uint64_t geometryMemoryBytes(const SceneDescription& d) {
  uint64_t bytes = 0;
  for (const MeshDesc& m : d.meshes) {
    bytes = saturatingAdd(bytes, meshBuildBytes(m.triangleCount(), m.positions.size()));
  }
  // A slanted cone enters the BVH in parts, each costing what a sphere does.
  uint64_t coneParts = 0;
  for (const ConeDesc& c : d.cones) {
    coneParts += static_cast<uint64_t>(
        bvhPartCount(Cone(c.base, c.baseRadius, c.apex, c.apexRadius, c.material)));
  }
  const uint64_t primitives = d.spheres.size() + d.planes.size() + coneParts;
  bytes = saturatingAdd(bytes, saturatingMultiply(primitives, kBytesPerOtherPrimitive));
  if (d.environment) {
    const CubeMapDesc& cube = *d.environment;
    for (int f = 0; f < 6; ++f) {
      const int width = cube.faceWidth(f), height = cube.faceHeight(f);
      const uint64_t texels = static_cast<uint64_t>(width) * static_cast<uint64_t>(height);
      // The description's copy, its wire copy and the scene's with its mip levels: as 3 bytes,
      // 3 bytes and packed 4-byte texels (while the levels above the finest are built, a float
      // copy of the second level) where the faces are kept as bytes, else as floats.
      const uint64_t pyramid = mipLevelsTexels(width, height);
      const uint64_t faceBytes =
          cube.keptAsBytes() ? saturatingAdd(saturatingAdd(saturatingMultiply(2 * texels, 3),
                                                           saturatingMultiply(pyramid, 4)),
                                             saturatingMultiply(texels / 4, sizeof(Color)))
                             : saturatingMultiply(2 * texels + pyramid, sizeof(Color));
      bytes = saturatingAdd(bytes, faceBytes);
    }
  }
  return bytes;
}

void checkGeometryFits(const SceneDescription& d, const MemoryLimit& limit) {
  const uint64_t needed = geometryMemoryBytes(d);
  if (needed > limit.bytes) {
    throw ResourceLimitError(
        memoryRefusal("the scene's geometry (" + std::to_string(d.triangleCount()) + " triangles)",
                      needed, limit, "simplify the meshes"));
  }
}

}  // namespace prism
