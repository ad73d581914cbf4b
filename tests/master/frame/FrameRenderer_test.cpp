#include "master/frame/FrameRenderer.h"

#include <gtest/gtest.h>

#include <cstring>

#include "common/geometry/TestMeshes.h"

namespace prism {
namespace {

// A small scene with every primitive kind, glass, a mirror, a checker and a smooth mesh.
SceneDescription mixedScene() {
  SceneDescription d;
  d.camera.position = {0, 2, 6};
  d.camera.lookAt = {0, 0.8f, 0};
  d.render.width = 61;
  d.render.height = 43;
  d.render.samplesPerPixel = 4;
  d.render.maxDepth = 6;
  d.render.seed = 42;
  d.background = Color(0.2f, 0.3f, 0.5f);
  MaterialDesc floor;
  floor.checker = CheckerDesc{};
  MaterialDesc glass;
  glass.diffuse = Color(0.0f);
  glass.transmittance = Color(1.0f);
  MaterialDesc mirror;
  mirror.diffuse = Color(0.1f);
  mirror.reflectance = Color(0.8f);
  mirror.specular = Color(0.5f);
  d.materials = {floor, glass, mirror};
  d.planes.push_back({{0, 0, 0}, {0, 1, 0}, 0, {}});
  d.spheres.push_back({{-1, 1, 0}, 1.0f, 1, {}});
  ConeDesc cone;
  cone.base = {2, 0, -1};
  cone.apex = {2, 1.5f, -1};
  cone.baseRadius = 0.5f;
  cone.apexRadius = 0.2f;
  cone.material = 2;
  d.cones.push_back(cone);
  const test::TestMesh ball = test::icosphere(2, Vec3(1, 0.6f, 1), 0.6f);
  MeshDesc mesh;
  mesh.positions = ball.positions;
  mesh.indices = ball.indices;
  for (const Vec3& p : ball.positions) mesh.normals.push_back(glm::normalize(p - Vec3(1, 0.6f, 1)));
  mesh.material = 2;
  d.meshes.push_back(mesh);
  PointLightDesc light;
  light.position = {3, 5, 4};
  light.intensity = Color(40.0f);
  d.lights.push_back(light);
  return d;
}

bool bitIdentical(const ImageRgb& a, const ImageRgb& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Color)) == 0;
}

TEST(FrameRenderer, ImageIsBitIdenticalForAnyThreadCountAndTileSize) {
  const Scene scene(mixedScene());
  FrameOptions reference;
  reference.distribution.threads = 1;
  reference.distribution.tileSize = 8;
  const FrameResult base = renderFrame(scene, reference);
  for (int threads : {1, 2, 3}) {
    for (int tile : {8, 13, 64}) {
      FrameOptions options;
      options.distribution.threads = threads;
      options.distribution.tileSize = tile;
      const FrameResult other = renderFrame(scene, options);
      EXPECT_TRUE(bitIdentical(base.image, other.image)) << threads << " threads, tile " << tile;
      EXPECT_EQ(other.rays.total(), base.rays.total());
    }
  }
}

TEST(FrameRenderer, SeedChangesTheSamplesButNotTheMean) {
  SceneDescription d = mixedScene();
  const FrameResult a = renderFrame(Scene(d), {});
  d.render.seed = 43;
  const FrameResult b = renderFrame(Scene(d), {});
  EXPECT_FALSE(bitIdentical(a.image, b.image));
  double sumA = 0, sumB = 0;
  for (size_t i = 0; i < a.image.pixels.size(); ++i) {
    sumA += a.image.pixels[i].x;
    sumB += b.image.pixels[i].x;
  }
  EXPECT_NEAR(sumA / sumB, 1.0, 0.02);
}

TEST(FrameRenderer, CountsOnePrimaryRayPerSampleAndEveryTile) {
  const SceneDescription d = mixedScene();
  const FrameResult f = renderFrame(Scene(d), {});
  EXPECT_EQ(f.rays.primary, static_cast<uint64_t>(d.render.width) * d.render.height * 4);
  EXPECT_GT(f.rays.shadow, 0u);
  EXPECT_GT(f.rays.secondary, 0u);
  EXPECT_GT(f.tileCount, 1u);
}

}  // namespace
}  // namespace prism
