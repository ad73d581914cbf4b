#include "scene/Scene.h"

#include <gtest/gtest.h>

namespace prism {
namespace {

// One triangle in the z = 0 plane, seen from +z, optionally with distinct vertex normals.
SceneDescription triangleScene(bool withNormals) {
  SceneDescription d;
  MeshDesc mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  if (withNormals) {
    mesh.normals = {glm::normalize(Vec3(-0.3f, -0.3f, 1.0f)), glm::normalize(Vec3(0.5f, 0, 1)),
                    glm::normalize(Vec3(0, 0.5f, 1))};
  }
  mesh.indices = {0, 1, 2};
  d.meshes.push_back(mesh);
  return d;
}

TEST(Scene, SmoothShadingInterpolatesVertexNormalsBarycentrically) {
  const SceneDescription d = triangleScene(true);
  const Scene scene(d);
  const float u = 0.2f, v = 0.5f;  // p = v0 + u·e1 + v·e2
  const Ray ray{Vec3(u, v, 3.0f), Vec3(0, 0, -1)};
  HitRecord hit;
  ASSERT_TRUE(scene.intersect(ray, hit));
  EXPECT_FLOAT_EQ(hit.t, 3.0f);
  const SurfaceHit s = scene.surface(ray, hit);
  const auto& n = d.meshes[0].normals;
  const Vec3 expected = glm::normalize((1 - u - v) * n[0] + u * n[1] + v * n[2]);
  EXPECT_NEAR(glm::dot(s.shadingNormal, expected), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(s.geometricNormal, Vec3(0, 0, 1)), 1.0f, 1e-6f);
  EXPECT_TRUE(s.frontFace);
}

TEST(Scene, FlatShadingWithoutNormalsUsesTheGeometricNormal) {
  const Scene scene(triangleScene(false));
  const Ray ray{Vec3(0.2f, 0.3f, 2.0f), Vec3(0, 0, -1)};
  HitRecord hit;
  ASSERT_TRUE(scene.intersect(ray, hit));
  const SurfaceHit s = scene.surface(ray, hit);
  EXPECT_EQ(s.shadingNormal, s.geometricNormal);
  EXPECT_NEAR(s.geometricNormal.z, 1.0f, 1e-6f);
}

TEST(Scene, BackFaceHitsAreMarkedAndNormalsFaceTheRay) {
  const Scene scene(triangleScene(true));
  const Ray ray{Vec3(0.2f, 0.3f, -2.0f), Vec3(0, 0, 1)};
  HitRecord hit;
  ASSERT_TRUE(scene.intersect(ray, hit));
  const SurfaceHit s = scene.surface(ray, hit);
  EXPECT_FALSE(s.frontFace);
  EXPECT_LT(s.geometricNormal.z, 0.0f);
  EXPECT_LT(s.shadingNormal.z, 0.0f);
}

TEST(Scene, ClosestOfPlaneSphereAndConeWins) {
  SceneDescription d;
  d.planes.push_back({{0, 0, 0}, {0, 0, 1}, 0, {}});
  d.spheres.push_back({{0, 0, 2}, 0.5f, 0, {}});
  ConeDesc cone;
  cone.base = {0, 0, 4};
  cone.apex = {0, 0, 5};
  cone.baseRadius = cone.apexRadius = 0.5f;
  d.cones.push_back(cone);
  const Scene scene(d);
  HitRecord hit;
  ASSERT_TRUE(scene.intersect(Ray{Vec3(0, 0, 10), Vec3(0, 0, -1)}, hit));
  EXPECT_FLOAT_EQ(hit.t, 7.5f);  // sphere top at z = 2.5 (the cone is open along this ray)
  ASSERT_TRUE(scene.intersect(Ray{Vec3(3, 0, 10), Vec3(0, 0, -1)}, hit));
  EXPECT_FLOAT_EQ(hit.t, 10.0f);  // the plane, outside the BVH
  ASSERT_TRUE(scene.intersect(Ray{Vec3(3, 0, 4.5f), Vec3(-1, 0, 0)}, hit));
  EXPECT_FLOAT_EQ(hit.t, 2.5f);  // cone wall at x = 0.5
}

TEST(Scene, OcclusionStopsAtTheRayEnd) {
  SceneDescription d;
  d.spheres.push_back({{0, 0, 5}, 1.0f, 0, {}});
  const Scene scene(d);
  EXPECT_TRUE(scene.occluded(Ray{Vec3(0), Vec3(0, 0, 1), 0.0f, 10.0f}));
  EXPECT_FALSE(scene.occluded(Ray{Vec3(0), Vec3(0, 0, 1), 0.0f, 3.9f}));
  EXPECT_FALSE(scene.occluded(Ray{Vec3(0), Vec3(0, 0, -1), 0.0f, 10.0f}));
}

TEST(Scene, ReportsWhatItBuilt) {
  SceneDescription d = triangleScene(false);
  d.spheres.push_back({{0, 0, 5}, 1.0f, 0, {}});
  d.planes.push_back({{0, 0, 0}, {0, 1, 0}, 0, {}});
  const Scene scene(d);
  const SceneBuildStats& s = scene.buildStats();
  EXPECT_EQ(s.triangles, 1u);
  EXPECT_EQ(s.spheres, 1u);
  EXPECT_EQ(s.planes, 1u);
  EXPECT_GE(s.bvh.nodeCount, 1u);
  EXPECT_GT(s.bvh.memoryBytes, 0u);
  EXPECT_GT(s.geometryBytes, 0u);
}

}  // namespace
}  // namespace prism
