#include "scene/GeometryMemory.h"

#include <gtest/gtest.h>

#include "geometry/ConeSegments.h"
#include "image/MipPyramid.h"

namespace prism {
namespace {

SceneDescription thousandTrianglesAndTwoSpheres() {
  SceneDescription d;
  MeshDesc mesh;
  mesh.positions.resize(600);
  mesh.indices.resize(3 * 1000);
  d.meshes.push_back(mesh);
  d.spheres.resize(2);
  return d;
}

TEST(GeometryMemory, CountsTrianglesVerticesAndPrimitives) {
  // 1000 x 212 + 600 x 64 + 2 x 448
  EXPECT_EQ(geometryMemoryBytes(thousandTrianglesAndTwoSpheres()), 251296u);
}

TEST(GeometryMemory, CountsCubeMapFacesWithTheirMipLevels) {
  SceneDescription d;
  d.environment.emplace();
  for (ImageRgb& face : d.environment->faces) face = ImageRgb(16, 16);
  // Six faces of 12-byte texels: the description's 256 and its wire copy's, and the scene's
  // 256 + 64 + 16 + 4 + 1 with the levels.
  EXPECT_EQ(geometryMemoryBytes(d), 6u * 12u * (2u * 256u + 341u));
  // Faces kept as bytes: 3-byte texels in the description and on the wire, 4-byte packed
  // levels, and the float copy of the 8x8 level while the levels above are made.
  for (int f = 0; f < 6; ++f) {
    d.environment->faces[f] = ImageRgb();
    d.environment->srgbFaces[f] = SrgbImage{16, 16, std::vector<uint8_t>(3 * 256)};
  }
  EXPECT_EQ(geometryMemoryBytes(d), 6u * (3u * 2u * 256u + 4u * 341u + 12u * 64u));
}

TEST(GeometryMemory, CountsEachPartASlantedConeEntersTheBvhAs) {
  SceneDescription d;
  ConeDesc upright;  // default: base at the origin, apex one unit up, pointed
  upright.apex = {0, 5, 0};
  upright.baseRadius = upright.apexRadius = 0.1f;
  d.cones.push_back(upright);
  EXPECT_EQ(geometryMemoryBytes(d), 448u);  // an axis-aligned cylinder stays whole
  ConeDesc slanted = upright;
  slanted.apex = {4, 4, 4};
  d.cones.push_back(slanted);
  // Each of the parts bvhParts makes costs a sphere's 448 bytes.
  const std::vector<Cone> parts = bvhParts(Cone(slanted.base, 0.1f, slanted.apex, 0.1f, 0));
  ASSERT_GT(parts.size(), 1u);
  EXPECT_EQ(geometryMemoryBytes(d), 448u * (1 + parts.size()));
}

TEST(GeometryMemory, RefusesOneByteShortWithTheBytesAndTheLimit) {
  const SceneDescription d = thousandTrianglesAndTwoSpheres();
  EXPECT_NO_THROW(checkGeometryFits(d, {251296, "test"}));
  try {
    checkGeometryFits(d, {251295, "--memory-limit"});
    FAIL() << "not refused";
  } catch (const ResourceLimitError& e) {
    EXPECT_STREQ(e.what(),
                 "the scene's geometry (1000 triangles) needs 245.4 KiB (251296 bytes); the "
                 "memory limit is 245.4 KiB (251295 bytes, --memory-limit): simplify the meshes");
  }
}

// A texture counts with its copies and pyramid: a 64² byte texture's description and wire copies
// (3 bytes a texel each), its packed pyramid (4 bytes a texel over 4/3 of them) and the float
// copy of its second level; a float texture's copies and pyramid as 12-byte texels.
TEST(GeometryMemory, TexturesCountWithTheirPyramids) {
  TextureDesc bytes;
  bytes.srgb = SrgbImage{64, 64, std::vector<uint8_t>(64 * 64 * 3)};
  const uint64_t texels = 64 * 64, pyramid = mipLevelsTexels(64, 64);
  EXPECT_EQ(textureMemoryBytes(bytes), 2 * texels * 3 + pyramid * 4 + texels / 4 * 12);
  TextureDesc floats;
  floats.linear = ImageRgb(64, 64);
  EXPECT_EQ(textureMemoryBytes(floats), (2 * texels + pyramid) * 12);
  SceneDescription d;
  const uint64_t without = geometryMemoryBytes(d);
  d.textures = {bytes, floats};
  EXPECT_EQ(geometryMemoryBytes(d),
            without + textureMemoryBytes(bytes) + textureMemoryBytes(floats));
}

}  // namespace
}  // namespace prism
