// The wire form of a built geometry: what a slave decodes is what rank 0 built, member for
// member and hit for hit, and bytes that are not a geometry are refused before any walk.
#include "wire/GeometryCodec.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "parse/SceneLoader.h"
#include "scene/Scene.h"
#include "wire/FieldCodec.h"
#include "wire/Messages.h"

namespace prism::wire {
namespace {

SceneDescription sceneAt(const std::string& path) {
  return loadScene(std::string(PRISM_SOURCE_DIR) + path);
}

// Rays from around the scene's box towards points inside it, so most of them hit something.
std::vector<Ray> raysThrough(const Aabb& box, int count) {
  std::mt19937 random(54);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const Vec3 center = box.empty() ? Vec3(0.0f) : box.center();
  const float reach = box.empty() ? 10.0f : 2.0f * glm::length(box.extent()) + 1.0f;
  std::vector<Ray> rays;
  for (int i = 0; i < count; ++i) {
    const Vec3 from =
        center + reach * glm::normalize(Vec3(unit(random), unit(random), unit(random)) - 0.5f);
    const Vec3 to = box.empty() ? center
                                : box.lower + Vec3(unit(random), unit(random), unit(random)) *
                                                  (box.upper - box.lower);
    Ray ray;
    ray.origin = from;
    ray.direction = glm::normalize(to - from);
    rays.push_back(ray);
  }
  return rays;
}

struct Walked {
  int hits = 0;
  std::vector<float> numbers;  // every hit's t, u, v and surface point, and the shadow answers
};

Walked walk(const SceneGeometry& g, const std::vector<Ray>& rays) {
  Walked w;
  for (const Ray& ray : rays) {
    HitRecord hit;
    const bool found = g.intersect(ray, hit);
    w.numbers.push_back(found ? 1.0f : 0.0f);
    w.numbers.push_back(g.occluded(ray) ? 1.0f : 0.0f);
    if (!found) continue;
    ++w.hits;
    SurfaceHit s;
    g.surface(ray, hit, s);
    for (float x : {hit.t, hit.u, hit.v, static_cast<float>(hit.primitive), s.position.x,
                    s.position.y, s.position.z, s.shadingNormal.x, s.shadingNormal.y}) {
      w.numbers.push_back(x);
    }
  }
  return w;
}

class GeometryCodecScenes : public ::testing::TestWithParam<std::tuple<const char*, Traversal>> {};

// Packed (default.yaml: Möller–Trumbore, the wide walk's packs), listed triangles
// (full.yaml's plane-inside test, with spheres, cones and planes), each walk.
TEST_P(GeometryCodecScenes, ADecodedGeometryIsTheBuiltOneBitForBit) {
  const auto [path, traversal] = GetParam();
  const SceneDescription d = sceneAt(path);
  const Scene built(d, traversal);
  const std::vector<uint8_t> bytes = encode(built.geometry());
  const SceneGeometry decoded = decode<SceneGeometry>(decodeMessage(bytes));
  EXPECT_TRUE(sameFields(decoded, built.geometry()));
  EXPECT_EQ(encode(decoded), bytes);
  EXPECT_NO_THROW(checkGeometryFitsScene(decoded, d));

  const std::vector<Ray> rays = raysThrough(built.bounds(), 2000);
  const Walked fromBuild = walk(built.geometry(), rays);
  const Walked fromWire = walk(decoded, rays);
  EXPECT_GT(fromBuild.hits, 200);
  ASSERT_EQ(fromWire.numbers.size(), fromBuild.numbers.size());
  for (size_t i = 0; i < fromBuild.numbers.size(); ++i) {
    ASSERT_TRUE(std::memcmp(&fromWire.numbers[i], &fromBuild.numbers[i], sizeof(float)) == 0) << i;
  }

  // Through Scene, as a slave takes it: the same hits.
  SceneDescription copy = d;
  const Scene taken(copy, std::nullopt, decode<SceneGeometry>(decodeMessage(bytes)));
  EXPECT_EQ(walk(taken.geometry(), rays).numbers, fromBuild.numbers);
  EXPECT_EQ(taken.causticCasters().size(), built.causticCasters().size());
  EXPECT_EQ(taken.instructionSet(), built.instructionSet());
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, GeometryCodecScenes,
    ::testing::Combine(::testing::Values("/scenes/default.yaml", "/tests/data/scenes/full.yaml"),
                       ::testing::Values(Traversal::WideSimd, Traversal::WideScalarLeaves,
                                         Traversal::BinaryScalar)));

TEST(GeometryCodec, AGeometryOfAnotherSceneIsRefused) {
  const SceneDescription d = sceneAt("/scenes/default.yaml");
  SceneDescription other = d;
  other.planes.clear();
  const SceneGeometry g = decode<SceneGeometry>(decodeMessage(encode(Scene(other).geometry())));
  try {
    checkGeometryFitsScene(g, d);
    FAIL() << "accepted";
  } catch (const WireError& e) {
    EXPECT_NE(std::string(e.what()).find("geometry: built from another scene"), std::string::npos)
        << e.what();
  }
  SceneDescription fewerMaterials = d;
  fewerMaterials.materials.resize(1);
  EXPECT_THROW(checkGeometryFitsScene(g, fewerMaterials), WireError);
}

// Every byte of a small geometry's payload changed in turn (the envelope made valid again): each
// result is refused with WireError or decodes to a geometry that the walks can run on without
// reading outside its arrays (the sanitizer builds check that) or looping. The index checks
// are what refuse most of them.
TEST(GeometryCodec, EveryChangedByteIsRefusedOrWalksSafely) {
  for (const char* path : {"/scenes/lambert-plane.yaml", "/tests/data/scenes/full.yaml"}) {
    SceneDescription d = sceneAt(path);
    const Scene built(d);
    const std::vector<uint8_t> payload = decodeMessage(encode(built.geometry())).payload;
    const std::vector<Ray> rays = raysThrough(built.bounds(), 16);
    int refusedByTheChecks = 0, refused = 0;
    for (size_t at = 0; at < payload.size(); ++at) {
      for (const uint8_t change : {uint8_t{0xFF}, uint8_t{0x01}}) {
        std::vector<uint8_t> bad = payload;
        bad[at] = change == 0xFF ? 0xFF : static_cast<uint8_t>(bad[at] + 1);
        try {
          const SceneGeometry g =
              decode<SceneGeometry>(decodeMessage(encodeMessage(MessageType::Geometry, bad)));
          walk(g, rays);
        } catch (const WireError& e) {
          ++refused;
          refusedByTheChecks += std::string(e.what()).find("geometry: ") != std::string::npos;
        }
      }
    }
    EXPECT_GT(refused, 0) << path;
    EXPECT_GT(refusedByTheChecks, 0) << path;
  }
}

}  // namespace
}  // namespace prism::wire
