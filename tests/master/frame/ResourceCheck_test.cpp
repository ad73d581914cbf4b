#include "master/frame/ResourceCheck.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <functional>

namespace prism {
namespace {

const MemoryLimit k16GiB{16ull << 30, "test"};

std::string refusal(const std::function<void()>& check) {
  try {
    check();
  } catch (const ResourceLimitError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(ResourceCheck, RefusesAMillionByMillionImageWithTheMemoryItNeeds) {
  RenderSettings s;
  s.width = 1000000;
  s.height = 1000000;
  EXPECT_EQ(frameMemoryBytes(s), 24000000000000ull);  // 2 x 10^12 pixels x 12 bytes
  EXPECT_EQ(refusal([&] { checkRenderFits(s, k16GiB); }),
            "a 1000000x1000000 image's frame buffer needs 21.8 TiB (24000000000000 bytes); the "
            "memory limit is 16.0 GiB (17179869184 bytes, test): reduce --width/--height");
}

TEST(ResourceCheck, AcceptsOrdinaryImages) {
  RenderSettings s;
  s.width = 7680;
  s.height = 4320;
  EXPECT_NO_THROW(checkRenderFits(s, k16GiB));
  EXPECT_NO_THROW(checkTilesFit(s, 0, k16GiB));
}

TEST(ResourceCheck, TileCountHasABoundAndItsBookkeepingAMemoryCost) {
  RenderSettings s;
  s.width = 100000;
  s.height = 100000;
  EXPECT_EQ(tileCount(s, 1), 10000000000ull);
  EXPECT_EQ(tileCount(s, 0), 12500ull * 12500ull);  // automatic: tiles of at least 8 pixels
  EXPECT_EQ(refusal([&] { checkTilesFit(s, 1, k16GiB); }),
            "a 100000x100000 image in 1-pixel tiles makes 10000000000 tiles; at most 16777216 "
            "are allowed (raise --tile-size)");
  s.width = s.height = 4096;  // 2^24 one-pixel tiles: the bound itself
  EXPECT_EQ(tileMemoryBytes(tileCount(s, 1)), 1073741824ull);
  EXPECT_EQ(refusal([&] {
              checkTilesFit(s, 1, {512ull << 20, "test"});
            }),
            "16777216 tiles' bookkeeping needs 1.0 GiB (1073741824 bytes); the memory limit is "
            "512.0 MiB (536870912 bytes, test): raise --tile-size");
  EXPECT_NO_THROW(checkTilesFit(s, 1, k16GiB));
}

// 10^12 photons at 156 bytes each (three 28-byte copies, a 4-byte index, ~8 bytes of tree, the
// tree's 16-byte leaf-order copy, the gather's 44-byte disc and radius) is 1.56e14 bytes =
// 141.9 TiB: refused on a 16 GiB machine before anything is traced.
TEST(ResourceCheck, RefusesAbsurdPhotonCountsWithTheMemoryTheyNeed) {
  CausticSettings c;
  c.method = CausticMethod::PhotonMap;
  c.photons = 1000000000000ull;
  EXPECT_EQ(photonMemoryBytes(c), 156000000000000ull);
  EXPECT_EQ(refusal([&] { checkCausticsFit(c, 1, k16GiB); }),
            "1000000000000 photons per pass needs 141.9 TiB (156000000000000 bytes); the memory "
            "limit is 16.0 GiB (17179869184 bytes, test): reduce --photons, or use more --passes "
            "of fewer");
  c.photons = 10000000;  // 10 M photons: under 1 GiB
  EXPECT_NO_THROW(checkCausticsFit(c, 1, k16GiB));
  c.method = CausticMethod::None;  // no photon map, no memory, whatever the count says
  c.photons = 1000000000000ull;
  EXPECT_EQ(photonMemoryBytes(c), 0u);
  EXPECT_NO_THROW(checkCausticsFit(c, 1, k16GiB));
}

// Caustic maps at 4096 texels a side for 8 lights, at least one view each: 8 · 4096² texels of
// 132 bytes (receiver 36, caster 28, lookup 32, the build's flux and blur buffers 3 · 12) is
// 17.7 GB, refused on a 16 GiB machine before any map is built; the default 512 needs 66 MiB.
TEST(ResourceCheck, RefusesCausticMapsLargerThanMemoryWithWhatTheyNeed) {
  CausticSettings c;
  c.method = CausticMethod::CausticMap;
  c.mapResolution = 4096;
  EXPECT_EQ(causticMapMemoryBytes(c, 8), 8ull * 4096 * 4096 * 132);
  EXPECT_EQ(refusal([&] { checkCausticsFit(c, 8, k16GiB); }),
            "caustic maps of 8 lights at 4096 texels a side (one view a light, at least) needs "
            "16.5 GiB (17716740096 bytes); the memory limit is 16.0 GiB (17179869184 bytes, "
            "test): reduce --map-resolution");
  EXPECT_NO_THROW(checkCausticsFit(c, 2, k16GiB));  // 4.1 GiB
  c.mapResolution = 512;
  EXPECT_EQ(causticMapMemoryBytes(c, 2), 69206016u);
  c.method = CausticMethod::PhotonMap;  // no maps, whatever the resolution says
  c.mapResolution = 4096;
  EXPECT_EQ(causticMapMemoryBytes(c, 8), 0u);
  // The run's total counts them too.
  SceneDescription d;
  d.caustics.method = CausticMethod::CausticMap;
  d.caustics.mapResolution = 512;
  d.lights.resize(2);
  d.render.width = d.render.height = 16;
  EXPECT_THAT(refusal([&] {
                checkSceneFits(d, 0, {60000000, "test"});
              }),
              ::testing::HasSubstr("caustics 66.0 MiB"));
}

TEST(ResourceCheck, GeometryCountsTrianglesVerticesAndPrimitives) {
  SceneDescription d;
  MeshDesc mesh;
  mesh.positions.resize(600);
  mesh.indices.resize(3 * 1000);
  d.meshes.push_back(mesh);
  d.spheres.resize(2);
  // 1000 x 212 + 600 x 64 + 2 x 448
  EXPECT_EQ(geometryMemoryBytes(d), 251296u);
  d.render.width = 100;
  d.render.height = 100;  // frame 240000, 169 automatic tiles: 10816
  EXPECT_NO_THROW(checkSceneFits(d, 0, {251296 + 240000 + 10816, "test"}));
  EXPECT_EQ(refusal([&] {
              checkSceneFits(d, 0, {251295, "test"});
            }),
            "the scene's geometry (1000 triangles) needs 245.4 KiB (251296 bytes); the memory "
            "limit is 245.4 KiB (251295 bytes, test): simplify the meshes");
  EXPECT_EQ(refusal([&] {
              checkSceneFits(d, 0, {500000, "test"});
            }),
            "the run (geometry 245.4 KiB, frame 234.4 KiB, caustics 0 B) needs 490.3 KiB (502112 "
            "bytes); the memory limit is 488.3 KiB (500000 bytes, test): reduce what is largest");
}

}  // namespace
}  // namespace prism
