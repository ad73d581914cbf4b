#include "scene/Scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "../geometry/TestMeshes.h"
#include "accel/PrimitiveRef.h"
#include "master/frame/FrameRenderer.h"
#include "math/Random.h"
#include "parse/SceneLoader.h"

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
  EXPECT_EQ(s.spheres.count, 1u);
  EXPECT_EQ(s.spheres.bvhParts, 1u);
  EXPECT_EQ(s.planes, 1u);
  EXPECT_GE(s.bvh.nodeCount, 1u);
  EXPECT_GT(s.bvh.memoryBytes, 0u);
  EXPECT_GT(s.geometryBytes, 0u);
}

// Once the wide BVH and its packs exist, the binary tree and the triangle array are dropped:
// the packs answer for the triangles' vertices, mesh and face.
TEST(Scene, PackedScenesKeepOnlyTheWideTreeAndThePacks) {
  SceneDescription d;
  const test::TestMesh ball = test::icosphere(3, Vec3(0.0f), 1.0f);
  MeshDesc mesh;
  mesh.positions = ball.positions;
  mesh.indices = ball.indices;
  d.meshes.push_back(mesh);
  d.meshes.push_back(mesh);  // a second mesh, so faces are numbered within each
  for (Vec3& p : d.meshes[1].positions) p += Vec3(5, 0, 0);
  const Scene packed(d, Traversal::WideSimd), binary(d, Traversal::BinaryScalar);
  const SceneBuildStats& s = packed.buildStats();
  EXPECT_TRUE(s.binaryBvhReleased);
  EXPECT_EQ(s.accelerationBytes(), s.wideBvh.memoryBytes + s.packBytes);
  EXPECT_EQ(s.triangles, 2 * ball.indices.size() / 3);
  // Shading data only: the mesh indices, 12 bytes a triangle.
  EXPECT_LT(s.geometryBytes, s.triangles * 13);
  EXPECT_FALSE(binary.buildStats().binaryBvhReleased);
  Pcg32 rng(2, 2);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 target(5.0f * (i % 2) + rng.nextFloat() - 0.5f, rng.nextFloat() - 0.5f, 0.0f);
    const Ray ray{Vec3(target.x, target.y, 4.0f), Vec3(0, 0, -1)};
    HitRecord a, b;
    const bool hit = packed.intersect(ray, a);
    ASSERT_EQ(hit, binary.intersect(ray, b)) << i;
    if (!hit) continue;
    ASSERT_EQ(a.t, b.t) << i;
    EXPECT_EQ(packed.meshFace(a), binary.meshFace(b)) << i;
    const SurfaceHit sa = packed.surface(ray, a), sb = binary.surface(ray, b);
    EXPECT_EQ(sa.geometricNormal, sb.geometricNormal) << i;
    EXPECT_EQ(sa.position, sb.position) << i;
  }
}

// Leaves of spheres and cones only take no triangle pack (the wide BVH points at their entries),
// and the packed walk still answers every ray as the binary walk does, in leaves with and
// without triangles.
TEST(Scene, LeavesWithoutTrianglesTakeNoPackAndAnswerAsTheBinaryWalk) {
  SceneDescription d;
  Pcg32 rng(7, 3);
  const auto inBox = [&] {
    return Vec3(rng.nextFloat() * 10 - 5, rng.nextFloat() * 10 - 5, rng.nextFloat() * 10 - 5);
  };
  for (int i = 0; i < 300; ++i) {
    SphereDesc sphere;
    sphere.center = inBox();
    sphere.radius = 0.1f + 0.2f * rng.nextFloat();
    d.spheres.push_back(sphere);
  }
  for (int i = 0; i < 150; ++i) {
    ConeDesc cone;
    cone.base = inBox();
    cone.baseRadius = 0.1f;
    cone.apex = cone.base + 2.0f * (inBox() / 5.0f);
    cone.apexRadius = 0.05f;
    d.cones.push_back(cone);
  }
  for (int i = 0; i < 150; ++i) {
    DiscDesc disc;
    disc.center = inBox();
    disc.normal = glm::normalize(inBox() + Vec3(0.01f));
    disc.radius = 0.1f + 0.3f * rng.nextFloat();
    d.discs.push_back(disc);
  }
  const Scene alone(d, Traversal::WideSimd);
  EXPECT_EQ(alone.buildStats().packBytes, 0u);

  const test::TestMesh ball = test::icosphere(2, Vec3(0.0f), 2.0f);
  MeshDesc mesh;
  mesh.positions = ball.positions;
  mesh.indices = ball.indices;
  d.meshes.push_back(mesh);
  const Scene mixed(d, Traversal::WideSimd), binary(d, Traversal::BinaryScalar);
  EXPECT_GT(mixed.buildStats().packBytes, 0u);
  std::map<PrimitiveKind, size_t> hits;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 origin = 1.6f * inBox();
    const Ray ray{origin, glm::normalize(inBox() - origin)};
    HitRecord a, b;
    const bool hit = mixed.intersect(ray, a);
    ASSERT_EQ(hit, binary.intersect(ray, b)) << i;
    ASSERT_EQ(mixed.occluded(ray), binary.occluded(ray)) << i;
    if (!hit) continue;
    ASSERT_EQ(a.t, b.t) << i;
    ASSERT_EQ(PrimitiveRef::kind(a.primitive), PrimitiveRef::kind(b.primitive)) << i;
    ++hits[PrimitiveRef::kind(a.primitive)];
  }
  for (PrimitiveKind kind :
       {PrimitiveKind::Triangle, PrimitiveKind::Sphere, PrimitiveKind::Cone, PrimitiveKind::Disc}) {
    EXPECT_GT(hits[kind], 100u) << static_cast<int>(kind);  // every kind was hit
  }
}

// ---- caustic roles -------------------------------------------------------------------------

// Materials for the role tests: 0 glass (no diffuse), 1 diffuse, 2 mirror with some diffuse,
// 3 black (neither specular nor diffuse).
SceneDescription roleScene() {
  SceneDescription d;
  MaterialDesc glass;
  glass.diffuse = Color(0.0f);
  glass.transmittance = Color(1.0f);
  MaterialDesc diffuse;
  diffuse.diffuse = Color(0.5f);
  MaterialDesc mirror;
  mirror.diffuse = Color(0.2f);
  mirror.reflectance = Color(0.7f);
  MaterialDesc black;
  black.diffuse = Color(0.0f);
  d.materials = {glass, diffuse, mirror, black};
  return d;
}

// The caustic bits of whatever a ray straight down from (x, 10, z) hits first.
uint8_t causticBitsBelow(const Scene& scene, float x, float z) {
  const Ray ray{Vec3(x, 10.0f, z), Vec3(0, -1, 0)};
  HitRecord hit;
  EXPECT_TRUE(scene.intersect(ray, hit)) << x << ", " << z;
  return scene.surface(ray, hit).caustic;
}

TEST(SceneCaustics, AutoRoleFollowsTheMaterial) {
  SceneDescription d = roleScene();
  // Four spheres in a row along x, one per material, all with the automatic role.
  for (uint32_t m = 0; m < 4; ++m) d.spheres.push_back({{3.0f * m, 0, 0}, 1.0f, m, {}});
  const Scene scene(d);
  EXPECT_EQ(causticBitsBelow(scene, 0, 0), kCastsCaustics);     // glass casts only
  EXPECT_EQ(causticBitsBelow(scene, 3, 0), kReceivesCaustics);  // diffuse receives only
  EXPECT_EQ(causticBitsBelow(scene, 6, 0), kCastsCaustics | kReceivesCaustics);  // both
  EXPECT_EQ(causticBitsBelow(scene, 9, 0), 0);                                   // black: neither
  // Two casters (glass and mirror), with their exact bounding spheres.
  const auto& casters = scene.causticCasters();
  ASSERT_EQ(casters.size(), 2u);
  EXPECT_FALSE(casters[0].plane);
  EXPECT_EQ(casters[0].center, Vec3(0, 0, 0));
  EXPECT_FLOAT_EQ(casters[0].radius, 1.0f);
  EXPECT_EQ(casters[1].center, Vec3(6, 0, 0));
}

TEST(SceneCaustics, CheckerCountsAsDiffuse) {
  SceneDescription d = roleScene();
  d.materials[3].checker = CheckerDesc{};
  d.spheres.push_back({{0, 0, 0}, 1.0f, 3, {}});
  EXPECT_EQ(causticBitsBelow(Scene(d), 0, 0), kReceivesCaustics);
}

TEST(SceneCaustics, ForcedRolesAreTakenAtTheirWord) {
  SceneDescription d = roleScene();
  d.spheres.push_back({{0, 0, 0}, 1.0f, 0, {}, CausticRole::Receive});  // glass that receives
  d.spheres.push_back({{3, 0, 0}, 1.0f, 1, {}, CausticRole::Cast});     // diffuse that casts
  d.spheres.push_back({{6, 0, 0}, 1.0f, 3, {}, CausticRole::Both});     // black, both
  d.spheres.push_back({{9, 0, 0}, 1.0f, 2, {}, CausticRole::Off});      // mirror, off
  const Scene scene(d);
  EXPECT_EQ(causticBitsBelow(scene, 0, 0), kReceivesCaustics);
  EXPECT_EQ(causticBitsBelow(scene, 3, 0), kCastsCaustics);
  EXPECT_EQ(causticBitsBelow(scene, 6, 0), kCastsCaustics | kReceivesCaustics);
  EXPECT_EQ(causticBitsBelow(scene, 9, 0), 0);
  const auto& casters = scene.causticCasters();
  ASSERT_EQ(casters.size(), 2u);
  EXPECT_EQ(casters[0].center, Vec3(3, 0, 0));
  EXPECT_EQ(casters[1].center, Vec3(6, 0, 0));
}

TEST(SceneCaustics, EveryPrimitiveKindResolvesItsRole) {
  SceneDescription d = roleScene();
  d.planes.push_back({{0, -2, 0}, {0, 1, 0}, 1, {}});  // diffuse floor: receives
  ConeDesc cone;  // a glass cylinder of radius 1 along z from z = -1 to z = 1 at x = 4
  cone.base = {4, 0, -1};
  cone.apex = {4, 0, 1};
  cone.baseRadius = cone.apexRadius = 1.0f;
  cone.material = 0;
  cone.caustic = CausticRole::Both;
  d.cones.push_back(cone);
  MeshDesc mesh;  // a mirror triangle at y = 1 around x = 8
  mesh.positions = {{7, 1, -1}, {9, 1, -1}, {8, 1, 2}};
  mesh.indices = {0, 2, 1};
  mesh.material = 2;
  d.meshes.push_back(mesh);
  const Scene scene(d);
  EXPECT_EQ(causticBitsBelow(scene, -5, 0), kReceivesCaustics);
  EXPECT_EQ(causticBitsBelow(scene, 4.5f, 0), kCastsCaustics | kReceivesCaustics);
  EXPECT_EQ(causticBitsBelow(scene, 8, 0), kCastsCaustics | kReceivesCaustics);

  // Casters: the cone and the mesh by the bounding spheres of their boxes. The cylinder's box is
  // [3,5]×[-1,1]×[-1,1]: centre (4,0,0), half-diagonal √3. The triangle's is [7,9]×[1,1]×[-1,2]:
  // centre (8,1,0.5), half-diagonal √(1 + 2.25) = √3.25.
  const auto& casters = scene.causticCasters();
  ASSERT_EQ(casters.size(), 2u);
  EXPECT_NEAR(glm::length(casters[0].center - Vec3(4, 0, 0)), 0.0f, 1e-6f);
  EXPECT_NEAR(casters[0].radius, std::sqrt(3.0f), 1e-5f);
  EXPECT_NEAR(glm::length(casters[1].center - Vec3(8, 1, 0.5f)), 0.0f, 1e-6f);
  EXPECT_NEAR(casters[1].radius, std::sqrt(3.25f), 1e-5f);
}

TEST(SceneCaustics, CastingPlaneIsAnUnboundedCaster) {
  SceneDescription d = roleScene();
  d.planes.push_back({{0, 2, 0}, {0, 2, 0}, 2, {}});  // mirror plane y = 2, normal not unit
  const Scene scene(d);
  ASSERT_EQ(scene.causticCasters().size(), 1u);
  const CasterBounds& c = scene.causticCasters()[0];
  EXPECT_TRUE(c.plane);
  EXPECT_EQ(c.normal, Vec3(0, 1, 0));
  EXPECT_FLOAT_EQ(c.offset, 2.0f);
}

TEST(SceneCaustics, NoCasterWhenEverythingIsOffOrDiffuse) {
  SceneDescription d = roleScene();
  d.spheres.push_back({{0, 0, 0}, 1.0f, 0, {}, CausticRole::Off});
  d.spheres.push_back({{3, 0, 0}, 1.0f, 1, {}});
  d.planes.push_back({{0, -2, 0}, {0, 1, 0}, 2, {}, CausticRole::Receive});
  const Scene scene(d);
  EXPECT_TRUE(scene.causticCasters().empty());
  EXPECT_EQ(causticBitsBelow(scene, 0, 0), 0);
  EXPECT_EQ(causticBitsBelow(scene, -5, 0), kReceivesCaustics);
}

TEST(SceneCaustics, SettingsArriveUnchanged) {
  SceneDescription d = roleScene();
  d.caustics.method = CausticMethod::PhotonMap;
  d.caustics.photons = 1234;
  d.caustics.alpha = 0.5f;
  const Scene scene(d);
  EXPECT_EQ(scene.causticSettings().method, CausticMethod::PhotonMap);
  EXPECT_EQ(scene.causticSettings().photons, 1234u);
  EXPECT_FLOAT_EQ(scene.causticSettings().alpha, 0.5f);
}

// The wide SIMD walk against the binary scalar one it was collapsed from.

// `count` separate triangles, each a corner in the box low + [0, extent) and the other two
// within `size` of it on every axis.
MeshDesc triangleSoup(Pcg32& rng, int count, const Vec3& low, const Vec3& extent, float size) {
  MeshDesc soup;
  for (int t = 0; t < count; ++t) {
    // One draw per axis, in order: the arguments of a constructor are evaluated in any order.
    const float x = rng.nextFloat(), y = rng.nextFloat(), z = rng.nextFloat();
    const Vec3 corner = low + extent * Vec3(x, y, z);
    for (int k = 0; k < 3; ++k) {
      const float dx = rng.nextFloat(), dy = rng.nextFloat(), dz = rng.nextFloat();
      soup.positions.push_back(corner + size * Vec3(dx, dy, dz));
      soup.indices.push_back(static_cast<uint32_t>(soup.positions.size() - 1));
    }
  }
  return soup;
}

// `count` spheres centred in the box low + [0, extent), radii in [radius, radius + spread).
void addRandomSpheres(SceneDescription& d, Pcg32& rng, int count, const Vec3& low,
                      const Vec3& extent, float radius, float spread) {
  for (int s = 0; s < count; ++s) {
    SphereDesc sphere;
    const float x = rng.nextFloat(), y = rng.nextFloat(), z = rng.nextFloat();
    sphere.center = low + extent * Vec3(x, y, z);
    sphere.radius = radius + spread * rng.nextFloat();
    d.spheres.push_back(sphere);
  }
}

// A subdivided sphere, a wavy grid and a loose soup of small triangles, plus spheres and a cone
// sharing leaves with them: meshes with shared edges, thin slivers and mixed leaves. Large: 54 k
// triangles instead of 8.6 k, enough for the scene to gather and pack them on several threads.
SceneDescription traversalScene(TriangleTest test, bool large = false) {
  SceneDescription d;
  d.render.triangleTest = test;
  const test::TestMesh ball = test::icosphere(large ? 5 : 4, Vec3(0.3f, 0.1f, 0.2f), 1.2f);
  MeshDesc sphereMesh;
  sphereMesh.positions = ball.positions;
  sphereMesh.indices = ball.indices;
  d.meshes.push_back(sphereMesh);
  MeshDesc grid;
  const int n = large ? 130 : 40;
  for (int z = 0; z <= n; ++z) {
    for (int x = 0; x <= n; ++x) {
      const float fx = -3.0f + 6.0f * x / n, fz = -3.0f + 6.0f * z / n;
      grid.positions.push_back({fx, -1.5f + 0.3f * std::sin(3 * fx) * std::cos(2 * fz), fz});
    }
  }
  for (int z = 0; z < n; ++z) {
    for (int x = 0; x < n; ++x) {
      const uint32_t i = z * (n + 1) + x;
      grid.indices.insert(grid.indices.end(), {i, i + 1, i + n + 1, i + 1, i + n + 2, i + n + 1});
    }
  }
  d.meshes.push_back(grid);
  Pcg32 rng(5, 5);
  d.meshes.push_back(
      triangleSoup(rng, 300, Vec3(-3.0f, -1.5f, -3.0f), Vec3(6.0f, 4.0f, 6.0f), 0.2f));
  addRandomSpheres(d, rng, 20, Vec3(-3.0f, -1.0f, -3.0f), Vec3(6.0f, 3.0f, 6.0f), 0.1f, 0.2f);
  ConeDesc cone;
  cone.base = {1.5f, -1.5f, 1.5f};
  cone.apex = {1.5f, 0.5f, 1.5f};
  cone.baseRadius = 0.3f;
  cone.apexRadius = 0.1f;
  d.cones.push_back(cone);
  return d;
}

Ray randomRay(Pcg32& rng) {
  const Vec3 origin(rng.nextFloat() * 10 - 5, rng.nextFloat() * 10 - 5, rng.nextFloat() * 10 - 5);
  const Vec3 target(rng.nextFloat() * 4 - 2, rng.nextFloat() * 3 - 1.5f, rng.nextFloat() * 4 - 2);
  Ray ray{origin, glm::normalize(target - origin)};
  ray.tMax = (rng.nextUint() % 4 == 0) ? 5.0f : std::numeric_limits<float>::infinity();
  return ray;
}

void expectSameHits(TriangleTest test, bool large = false) {
  const SceneDescription d = traversalScene(test, large);
  const Scene wide(d, Traversal::WideSimd), binary(d, Traversal::BinaryScalar);
  ASSERT_EQ(wide.traversal(), Traversal::WideSimd);
  ASSERT_GT(wide.buildStats().wideBvh.nodeCount, 0u);
  Pcg32 rng(17, 1);
  int hits = 0, occludedCount = 0, samePrimitive = 0;
  for (int i = 0; i < 40000; ++i) {
    const Ray ray = randomRay(rng);
    HitRecord a, b;
    const bool hitA = wide.intersect(ray, a), hitB = binary.intersect(ray, b);
    ASSERT_EQ(hitA, hitB) << i;
    ASSERT_EQ(wide.occluded(ray), binary.occluded(ray)) << i;
    occludedCount += wide.occluded(ray) ? 1 : 0;
    if (!hitA) continue;
    ++hits;
    // Same distance bit for bit; the primitive may differ only on an exact tie in t.
    ASSERT_EQ(std::memcmp(&a.t, &b.t, sizeof(float)), 0) << i;
    // The two walks number primitives in their own BVH's order: compare what was hit.
    const PrimitiveKind kind = PrimitiveRef::kind(a.primitive);
    if (kind != PrimitiveRef::kind(b.primitive)) continue;
    if (kind != PrimitiveKind::Triangle ||
        (wide.meshFace(a) == binary.meshFace(b) && a.u == b.u && a.v == b.v)) {
      ++samePrimitive;
    }
  }
  EXPECT_GT(hits, 10000);
  EXPECT_EQ(occludedCount, hits);
  EXPECT_GE(samePrimitive, hits - 5);
}

TEST(SceneTraversal, WideWalkFindsTheBinaryWalksHitsWithMollerTrumbore) {
  expectSameHits(TriangleTest::MollerTrumbore);
}

TEST(SceneTraversal, WideWalkFindsTheBinaryWalksHitsWithPlaneThenInside) {
  expectSameHits(TriangleTest::PlaneThenInside);
}

TEST(SceneTraversal, WideWalkFindsTheBinaryWalksHitsWithWatertight) {
  expectSameHits(TriangleTest::Watertight);
}

// Above Scene.cpp's kParallelGatherMinTriangles the triangles are gathered, and their packs
// filled straight from the description, on every core: the packs must still hold each leaf's
// own triangles (the binary walk tests the gathered copies).
TEST(SceneTraversal, WideWalkFindsTheBinaryWalksHitsInALargeScene) {
  ASSERT_GE(traversalScene(TriangleTest::MollerTrumbore, true).triangleCount(), 50000u);
  expectSameHits(TriangleTest::MollerTrumbore, true);
}

// Through the whole scene (BVH, packs, double-precision lanes), rays from inside a closed mesh
// aimed exactly at its vertices and along its edges: the watertight test lets none out, in
// either walk. Möller–Trumbore, for comparison, lets some out. Without the robust slab test
// (accel/Bvh.h, kSlabFarScale) 6 of these rays escaped the wide walk and 50 the binary one:
// the boxes of the triangles around a vertex were missed, not the triangles.
TEST(SceneTraversal, WatertightScenesLetNoRayOutOfAClosedMesh) {
  SceneDescription d;
  const test::TestMesh ball = test::icosphere(4, Vec3(31.0f, -27.0f, 53.0f), 17.0f);
  MeshDesc mesh;
  mesh.positions = ball.positions;
  mesh.indices = ball.indices;
  d.meshes.push_back(mesh);
  const Vec3 inside = Vec3(31.0f, -27.0f, 53.0f) + Vec3(1.3f, -0.7f, 2.1f);
  std::vector<Ray> rays;
  Pcg32 rng(4, 4);
  for (size_t f = 0; f < ball.indices.size(); f += 3) {
    const Vec3& a = ball.positions[ball.indices[f]];
    const Vec3& b = ball.positions[ball.indices[f + 1]];
    rays.push_back({inside, glm::normalize(a - inside)});
    rays.push_back({inside, glm::normalize(glm::mix(a, b, rng.nextFloat()) - inside)});
  }
  int mollerEscapes = 0;
  for (TriangleTest test : {TriangleTest::Watertight, TriangleTest::MollerTrumbore}) {
    d.render.triangleTest = test;
    for (Traversal traversal : {Traversal::WideSimd, Traversal::BinaryScalar}) {
      const Scene scene(d, traversal);
      int escapes = 0;
      for (const Ray& ray : rays) {
        HitRecord hit;
        escapes += !scene.intersect(ray, hit);
      }
      if (test == TriangleTest::Watertight) {
        EXPECT_EQ(escapes, 0) << "of " << rays.size();
      } else {
        mollerEscapes += escapes;
      }
    }
  }
  EXPECT_GT(mollerEscapes, 0);
}

TEST(SceneTraversal, EmptyAndOnePrimitiveScenes) {
  const SceneDescription empty;
  const Scene scene(empty);
  HitRecord hit;
  const Ray ray{Vec3(0, 0, 5), Vec3(0, 0, -1)};
  EXPECT_FALSE(scene.intersect(ray, hit));
  EXPECT_FALSE(scene.occluded(ray));
  const Scene one(triangleScene(false));
  ASSERT_TRUE(one.intersect({Vec3(0.2f, 0.2f, 5), Vec3(0, 0, -1)}, hit));
  EXPECT_FLOAT_EQ(hit.t, 5.0f);
  EXPECT_TRUE(one.occluded({Vec3(0.2f, 0.2f, 5), Vec3(0, 0, -1)}));
  EXPECT_FALSE(one.occluded({Vec3(0.9f, 0.9f, 5), Vec3(0, 0, -1)}));
}

// Whole frames, shading, shadows, reflection, refraction and caustics included, come out bit
// for bit the same from both walks.
TEST(SceneTraversal, ImagesAreBitIdenticalToTheBinaryWalk) {
  for (const char* path : {"/scenes/default.yaml", "/scenes/caustic-glass-knot.yaml",
                           "/tests/data/nff/teapot-s3.nff", "/tests/data/nff/gears-s2.nff"}) {
    SceneDescription d = loadScene(std::string(PRISM_SOURCE_DIR) + path);
    d.render.width = 96;
    d.render.height = 72;
    d.render.samplesPerPixel = 1;
    d.caustics.photons = std::min<uint64_t>(d.caustics.photons, 20000);
    for (TriangleTest test :
         {TriangleTest::MollerTrumbore, TriangleTest::PlaneThenInside, TriangleTest::Watertight}) {
      d.render.triangleTest = test;
      FrameOptions options;
      options.distribution.threads = 1;
      const FrameResult a = renderFrame(Scene(d, Traversal::WideSimd), options);
      const FrameResult b = renderFrame(Scene(d, Traversal::BinaryScalar), options);
      ASSERT_EQ(a.image.width, b.image.width);
      int differing = 0;
      for (int y = 0; y < a.image.height; ++y) {
        for (int x = 0; x < a.image.width; ++x) {
          differing += std::memcmp(&a.image.at(x, y), &b.image.at(x, y), sizeof(Color)) != 0;
        }
      }
      EXPECT_EQ(differing, 0) << path;
    }
  }
}

// Many small spheres (leaves of spheres alone, which packets test with the rays in the lanes)
// over a floor plane (which shadow packets test ray by ray first), with a few triangles sharing
// leaves with them.
SceneDescription spheresOverAPlane() {
  SceneDescription d;
  Pcg32 rng(9, 2);
  addRandomSpheres(d, rng, 400, Vec3(-3.0f, -1.2f, -3.0f), Vec3(6.0f, 3.0f, 6.0f), 0.05f, 0.25f);
  PlaneDesc floor;
  floor.point = {0.0f, -1.0f, 0.0f};
  d.planes.push_back(floor);
  // A tilted wall behind, meeting the floor: rays meet both, and each must keep the nearer.
  PlaneDesc wall;
  wall.point = {0.0f, 0.0f, -2.5f};
  wall.normal = glm::normalize(Vec3(0.3f, 0.2f, 1.0f));
  d.planes.push_back(wall);
  d.meshes.push_back(
      triangleSoup(rng, 40, Vec3(-3.0f, -1.0f, -3.0f), Vec3(6.0f, 3.0f, 6.0f), 0.3f));
  return d;
}

// Packets of eight give each ray the answer it gets alone, bit for bit (t, primitive, u, v):
// coherent packets (a 4 × 2 pixel block of a camera; from below the floor plane, shadow-like
// packets towards a point) and incoherent ones (random rays), some rays dead (tMax < tMin),
// under both triangle tests the packs serve and in a scene of spheres over a plane, with the
// kernels of every instruction set this CPU runs (four rays to a vector up to x86-64-v2, eight
// from x86-64-v3 on).
TEST(SceneTraversal, PacketsOfEightAnswerAsSingleRays) {
  std::vector<std::pair<std::string, SceneDescription>> scenes;
  scenes.emplace_back("meshes, Moller-Trumbore", traversalScene(TriangleTest::MollerTrumbore));
  scenes.emplace_back("meshes, watertight", traversalScene(TriangleTest::Watertight));
  scenes.emplace_back("spheres over a plane", spheresOverAPlane());
  for (const auto& [name, d] : scenes) {
    int hits = 0, sphereHits = 0, blockedCount = 0, planeHits[2] = {0, 0};
    for (InstructionSet isa : instructionSetsIn(runnableInstructionSets())) {
      Scene scene(d);
      scene.useInstructionSet(isa);
      ASSERT_EQ(scene.instructionSet(), isa);
      const std::string where = name + ", " + instructionSetName(isa) + ", round ";
      Pcg32 rng(23, 4);
      for (int round = 0; round < 6000; ++round) {
        Ray rays[8];
        const int count = 1 + round % 8;
        const Vec3 eye(rng.nextFloat() * 10 - 5, 4.0f, 6.0f);
        const Vec3 light(rng.nextFloat() * 4 - 2, 5.0f, rng.nextFloat() * 4 - 2);
        const Vec3 below(rng.nextFloat() * 4 - 2, -2.0f, rng.nextFloat() * 4 - 2);
        for (int i = 0; i < count; ++i) {
          if (round % 3 == 0) {
            const Vec3 target(-1.0f + 0.02f * (i % 4), -0.5f + 0.02f * (i / 4),
                              0.1f * round / 6000);
            rays[i] = {eye, glm::normalize(target - eye)};
          } else if (round % 3 == 1) {
            // Towards the light from neighbouring points, stopping short of it; every other
            // packet from under the floor, which then blocks them all.
            const Vec3 from = (round % 6 == 1 ? Vec3(0.0f, -0.4f, 0.0f) : below) +
                              Vec3(0.03f * (i % 4), 0.0f, 0.03f * (i / 4));
            rays[i] = {from, glm::normalize(light - from)};
            rays[i].tMax = 0.999f * glm::length(light - from);
          } else {
            rays[i] = randomRay(rng);
          }
          if (round % 7 == 0 && i == 2) rays[i].tMax = -1.0f;  // dead ray
        }
        HitRecord packetHits[8];
        bool found[8], blocked[8];
        scene.intersect8(rays, count, packetHits, found);
        scene.occluded8(rays, count, blocked);
        for (int i = 0; i < count; ++i) {
          HitRecord single;
          const bool live = rays[i].tMax >= rays[i].tMin;
          const bool singleFound = live && scene.intersect(rays[i], single);
          ASSERT_EQ(found[i], singleFound) << where << round << " ray " << i;
          ASSERT_EQ(blocked[i], live && scene.occluded(rays[i])) << where << round << " ray " << i;
          blockedCount += blocked[i] ? 1 : 0;
          if (!singleFound) continue;
          ++hits;
          sphereHits += PrimitiveRef::kind(single.primitive) == PrimitiveKind::Sphere ? 1 : 0;
          if (PrimitiveRef::kind(single.primitive) == PrimitiveKind::Plane) {
            ++planeHits[PrimitiveRef::index(single.primitive)];
          }
          ASSERT_EQ(std::memcmp(&packetHits[i], &single, sizeof(HitRecord)), 0) << where << round;
        }
      }
    }
    EXPECT_GT(hits, 10000) << name;
    EXPECT_GT(blockedCount, 10000) << name;
    if (name == "spheres over a plane") {
      EXPECT_GT(sphereHits, 5000) << name;
      EXPECT_GT(planeHits[0], 1000) << name;
      EXPECT_GT(planeHits[1], 1000) << name;
    }
  }
}

// An empty packet and a packet of dead rays (tMax < tMin) trace nothing and find nothing.
TEST(SceneTraversal, PacketsWithoutLiveRaysFindNothing) {
  Scene scene(traversalScene(TriangleTest::MollerTrumbore));
  HitRecord hits[8];
  bool found[8], blocked[8];
  scene.intersect8(nullptr, 0, hits, found);
  scene.occluded8(nullptr, 0, blocked);
  Ray dead[8];
  for (Ray& ray : dead) ray = {Vec3(0, 4, 6), glm::normalize(Vec3(0, -1, -1)), 1.0f, 0.5f};
  for (int i = 0; i < 8; ++i) found[i] = blocked[i] = true;
  scene.intersect8(dead, 8, hits, found);
  scene.occluded8(dead, 8, blocked);
  for (int i = 0; i < 8; ++i) {
    EXPECT_FALSE(found[i]) << i;
    EXPECT_FALSE(blocked[i]) << i;
  }
}

// The renderer sends a packet of bounces down the packet walk only when its directions agree in
// sign per axis and spread by at most RayPacket8's limit; rays outside the mask do not count.
TEST(SceneTraversal, CoherentDirectionsAgreeInSignAndSpreadLittle) {
  Ray rays[8];
  for (int i = 0; i < 8; ++i) {
    rays[i] = {Vec3(0.0f), glm::normalize(Vec3(0.3f + 0.01f * i, -0.5f, 0.8f - 0.01f * i))};
  }
  EXPECT_TRUE(Scene::coherentDirections(rays, 0xFFu));
  EXPECT_FALSE(Scene::coherentDirections(rays, 0u));
  Ray spread[8];
  std::copy(rays, rays + 8, spread);
  spread[5].direction = glm::normalize(Vec3(0.6f, -0.5f, 0.6f));  // 0.2 away in x
  EXPECT_FALSE(Scene::coherentDirections(spread, 0xFFu));
  EXPECT_TRUE(Scene::coherentDirections(spread, 0xFFu & ~(1u << 5)));  // left out: coherent
  Ray signs[8];
  std::copy(rays, rays + 8, signs);
  for (Ray& ray : signs) ray.direction = glm::normalize(Vec3(0.01f, -0.5f, 0.8f));
  signs[2].direction = glm::normalize(Vec3(-0.01f, -0.5f, 0.8f));  // close, but x changes sign
  EXPECT_FALSE(Scene::coherentDirections(signs, 0xFFu));
  EXPECT_TRUE(Scene::coherentDirections(signs, 0x3u));
}

// The kernels are chosen per scene: Auto takes the best this process runs, a set it cannot
// run is refused by name, and the packet tests take eight rays to a vector from x86-64-v3 on.
TEST(SceneTraversal, KernelsOfEveryRunnableInstructionSet) {
  Scene scene(traversalScene(TriangleTest::MollerTrumbore));
  EXPECT_EQ(scene.instructionSet(), bestInstructionSet(runnableInstructionSets()));
  EXPECT_EQ(scene.settings().instructionSet, scene.instructionSet());  // Auto resolved
  for (InstructionSet isa : instructionSetsIn(runnableInstructionSets())) {
    scene.useInstructionSet(isa);
    EXPECT_EQ(scene.instructionSet(), isa);
    EXPECT_EQ(scene.packetLanes(), isa >= InstructionSet::V3 ? 8 : 4) << instructionSetName(isa);
  }
  for (InstructionSet isa : {InstructionSet::V2, InstructionSet::V3, InstructionSet::V4}) {
    if (runnableInstructionSets() & maskOf(isa)) continue;
    try {
      scene.useInstructionSet(isa);
      ADD_FAILURE() << instructionSetName(isa) << " accepted on a CPU that cannot run it";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(instructionSetName(isa)), std::string::npos) << e.what();
    }
  }
  SceneDescription d = traversalScene(TriangleTest::MollerTrumbore);
  d.render.instructionSet = InstructionSet::Baseline;
  EXPECT_EQ(Scene(d).instructionSet(), InstructionSet::Baseline);
}

}  // namespace
}  // namespace prism
