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
    for (const ImageRgb& face : d.environment->faces) {
      // The description's copy, its wire copy and the scene's with its mip levels.
      const uint64_t texels = 2 * face.pixels.size() + mipLevelsTexels(face.width, face.height);
      bytes = saturatingAdd(bytes, saturatingMultiply(texels, sizeof(Color)));
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
