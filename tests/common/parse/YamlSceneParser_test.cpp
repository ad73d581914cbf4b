#include "parse/YamlSceneParser.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>

#include "image/ImageIo.h"
#include "parse/SceneLoader.h"

namespace prism {
namespace {

namespace fs = std::filesystem;

std::string dataPath(const std::string& relative) {
  return PRISM_TEST_DATA_DIR "/" + relative;
}

// Parses inline YAML as if it were a file in tests/data/scenes, so relative mesh paths resolve.
SceneDescription parse(const std::string& text) {
  return parseYamlScene(text, dataPath("scenes/inline.yaml"));
}

// The SceneError that parsing text throws; fails the test when it parses.
SceneError parseError(const std::string& text) {
  try {
    parse(text);
  } catch (const SceneError& e) {
    return e;
  }
  ADD_FAILURE() << "expected a SceneError for:\n" << text;
  return SceneError({}, "");
}

void expectVec(const Vec3& actual, const Vec3& expected, float tolerance = 1e-6f) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

// A private temporary folder per test.
class YamlSceneFiles : public testing::Test {
 protected:
  void SetUp() override {
    const auto* info = testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("prism_yaml_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) {
    const fs::path path = dir_ / name;
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
    return path.string();
  }

  fs::path dir_;
};

// ---- good scenes ---------------------------------------------------------------------------

TEST(YamlSceneParser, MinimalSceneTakesEveryDefault) {
  const std::string path = dataPath("scenes/minimal.yaml");
  const SceneDescription s = parseYamlScene(readTextFile(path), path);
  const CameraDesc camera;
  const RenderSettings render;
  EXPECT_EQ(s.sourcePath, path);
  EXPECT_EQ(s.camera.projection, camera.projection);
  expectVec(s.camera.position, camera.position);
  expectVec(s.camera.lookAt, camera.lookAt);
  expectVec(s.camera.up, camera.up);
  EXPECT_EQ(s.camera.fovDegrees, camera.fovDegrees);
  EXPECT_EQ(s.camera.width, camera.width);
  EXPECT_EQ(s.camera.nearClip, camera.nearClip);
  EXPECT_EQ(s.render.width, render.width);
  EXPECT_EQ(s.render.height, render.height);
  EXPECT_EQ(s.render.samplesPerPixel, render.samplesPerPixel);
  EXPECT_EQ(s.render.maxDepth, render.maxDepth);
  EXPECT_EQ(s.render.minContribution, render.minContribution);
  EXPECT_EQ(s.render.seed, render.seed);
  EXPECT_EQ(s.render.exposure, render.exposure);
  EXPECT_EQ(s.render.triangleTest, render.triangleTest);
  expectVec(s.background, Color(0.0f));
  expectVec(s.ambientLight, Color(0.0f));
  EXPECT_FALSE(s.environment);
  EXPECT_TRUE(s.lights.empty());

  // The sphere names no material, so the built-in default is added for it.
  ASSERT_EQ(s.spheres.size(), 1u);
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.spheres[0].material, 0u);
  EXPECT_EQ(s.materials[0].name, "default");
  expectVec(s.materials[0].diffuse, Color(0.8f));
  EXPECT_EQ(s.spheres[0].loc.file, path);
  EXPECT_EQ(s.spheres[0].loc.line, 3);
  EXPECT_EQ(s.spheres[0].loc.column, 13);
}

TEST(YamlSceneParser, FullSceneReadsEveryKey) {
  const std::string path = dataPath("scenes/full.yaml");
  const SceneDescription s = parseYamlScene(readTextFile(path), path);

  EXPECT_EQ(s.camera.projection, Projection::Orthographic);
  expectVec(s.camera.position, {1, 2, 3});
  expectVec(s.camera.lookAt, {0, 1, 0});
  expectVec(s.camera.up, {0, 0, 1});
  EXPECT_FLOAT_EQ(s.camera.fovDegrees, 60.0f);
  EXPECT_FLOAT_EQ(s.camera.width, 4.5f);
  EXPECT_FLOAT_EQ(s.camera.nearClip, 0.25f);
  EXPECT_EQ(s.camera.loc.line, 3);

  EXPECT_EQ(s.render.width, 320);
  EXPECT_EQ(s.render.height, 200);
  EXPECT_EQ(s.render.samplesPerPixel, 16);
  EXPECT_EQ(s.render.maxDepth, 7);
  EXPECT_FLOAT_EQ(s.render.minContribution, 0.01f);
  EXPECT_EQ(s.render.seed, 12345678901ull);
  EXPECT_FLOAT_EQ(s.render.exposure, 2.5f);
  EXPECT_EQ(s.render.triangleTest, TriangleTest::PlaneThenInside);
  expectVec(s.background, {0.1f, 0.2f, 0.3f});
  expectVec(s.ambientLight, Color(0.05f));

  // floor and glass as written; the plain cone and the second triangle add the default.
  ASSERT_EQ(s.materials.size(), 3u);
  const MaterialDesc& floor = s.materials[0];
  EXPECT_EQ(floor.name, "floor");
  expectVec(floor.ambient, Color(1.0f));
  expectVec(floor.diffuse, {0.7f, 0.6f, 0.5f});
  ASSERT_TRUE(floor.checker);
  expectVec(floor.checker->colorA, Color(0.9f));
  expectVec(floor.checker->colorB, Color(0.1f));
  EXPECT_FLOAT_EQ(floor.checker->scale, 0.5f);
  expectVec(floor.specular, Color(0.2f));
  EXPECT_FLOAT_EQ(floor.shininess, 64.0f);
  expectVec(floor.reflectance, {0.1f, 0.2f, 0.3f});
  expectVec(floor.transmittance, Color(0.0f));
  EXPECT_FLOAT_EQ(floor.ior, 1.0f);
  EXPECT_FALSE(floor.fresnel);
  EXPECT_EQ(floor.loc.line, 22);
  EXPECT_EQ(floor.loc.column, 5);
  const MaterialDesc& glass = s.materials[1];
  EXPECT_EQ(glass.name, "glass");
  expectVec(glass.diffuse, Color(0.0f));
  expectVec(glass.transmittance, Color(0.9f));
  EXPECT_TRUE(glass.fresnel);
  EXPECT_FALSE(glass.checker);
  EXPECT_EQ(s.materials[2].name, "default");

  ASSERT_EQ(s.lights.size(), 2u);
  expectVec(s.lights[0].position, {0, 5, 0});
  expectVec(s.lights[0].intensity, {100, 90, 80});
  EXPECT_FLOAT_EQ(s.lights[0].attenuation.constant, 1.0f);
  EXPECT_FLOAT_EQ(s.lights[0].attenuation.linear, 0.5f);
  EXPECT_FLOAT_EQ(s.lights[0].attenuation.quadratic, 0.25f);
  expectVec(s.lights[1].intensity, Color(1.0f));  // the default
  EXPECT_FLOAT_EQ(s.lights[1].attenuation.constant, 0.0f);
  EXPECT_FLOAT_EQ(s.lights[1].attenuation.quadratic, 1.0f);

  ASSERT_EQ(s.spheres.size(), 1u);
  expectVec(s.spheres[0].center, {0, 1, 0});
  EXPECT_FLOAT_EQ(s.spheres[0].radius, 1.0f);
  EXPECT_EQ(s.spheres[0].material, 1u);

  ASSERT_EQ(s.planes.size(), 1u);
  expectVec(s.planes[0].normal, {0, 1, 0});  // normalised
  EXPECT_EQ(s.planes[0].material, 0u);

  ASSERT_EQ(s.cones.size(), 3u);
  EXPECT_FLOAT_EQ(s.cones[0].baseRadius, 1.0f);
  EXPECT_FLOAT_EQ(s.cones[0].apexRadius, 0.5f);
  expectVec(s.cones[0].apex, {2, 2, 0});
  EXPECT_FLOAT_EQ(s.cones[1].apexRadius, 0.0f);  // apex_radius defaults to a pointed cone
  EXPECT_EQ(s.cones[1].material, 2u);
  // The cylinder is a cone with equal radii.
  expectVec(s.cones[2].base, {-2, 0, 0});
  expectVec(s.cones[2].apex, {-2, 3, 0});
  EXPECT_FLOAT_EQ(s.cones[2].baseRadius, 0.25f);
  EXPECT_FLOAT_EQ(s.cones[2].apexRadius, 0.25f);
  EXPECT_EQ(s.cones[2].material, 1u);

  ASSERT_EQ(s.meshes.size(), 3u);
  EXPECT_EQ(s.triangleCount(), 4u);

  EXPECT_EQ(s.caustics.method, CausticMethod::PhotonMap);
  EXPECT_EQ(s.caustics.photons, 12345u);
  EXPECT_EQ(s.caustics.gather, 50);
  EXPECT_FLOAT_EQ(s.caustics.maxRadius, 0.2f);
  EXPECT_EQ(s.caustics.filter, PhotonFilter::Epanechnikov);
  EXPECT_EQ(s.caustics.maxBounces, 9);
  EXPECT_TRUE(s.caustics.progressive);
  EXPECT_EQ(s.caustics.passes, 7);
  EXPECT_FLOAT_EQ(s.caustics.alpha, 0.6f);
  EXPECT_FLOAT_EQ(s.caustics.radius, 0.05f);
  EXPECT_DOUBLE_EQ(s.caustics.timeBudgetSeconds, 2.5);

  EXPECT_EQ(s.spheres[0].caustic, CausticRole::Cast);
  EXPECT_EQ(s.planes[0].caustic, CausticRole::Receive);
  EXPECT_EQ(s.cones[0].caustic, CausticRole::Auto);  // not given
  EXPECT_EQ(s.cones[1].caustic, CausticRole::Both);
  EXPECT_EQ(s.cones[2].caustic, CausticRole::Off);  // the cylinder
  EXPECT_EQ(s.meshes[0].caustic, CausticRole::Both);
  EXPECT_EQ(s.meshes[1].caustic, CausticRole::Auto);
  EXPECT_EQ(s.meshes[2].caustic, CausticRole::Receive);
}

TEST(YamlSceneParser, GatherAutoTakesTheNoiseItAimsAt) {
  const SceneDescription s =
      parse("caustics:\n  method: photon_map\n  gather: auto\n  noise: 0.1\n");
  EXPECT_TRUE(s.caustics.automaticGather);
  EXPECT_FLOAT_EQ(s.caustics.gatherNoise, 0.1f);
  const SceneDescription fixed = parse("caustics:\n  gather: 30\n");
  EXPECT_FALSE(fixed.caustics.automaticGather);
  EXPECT_EQ(fixed.caustics.gather, 30);
}

// A budget bounds progressive passes: given alone it asks for them (a classic render, one pass,
// ignored it) and runs them until it ends unless the scene gives a count; a budget of 0 (none)
// asks for nothing.
TEST(YamlSceneParser, ATimeBudgetAsksForProgressivePassesUntilItEnds) {
  const SceneDescription s = parse("caustics:\n  method: photon_map\n  time_budget: 8\n");
  EXPECT_TRUE(s.caustics.progressive);
  EXPECT_DOUBLE_EQ(s.caustics.timeBudgetSeconds, 8.0);
  EXPECT_EQ(s.caustics.passes, kPassesUntilBudget);
  EXPECT_TRUE(passesUntilBudget(s.caustics));
  const SceneDescription counted = parse("caustics:\n  time_budget: 3\n  passes: 7\n");
  EXPECT_TRUE(counted.caustics.progressive);
  EXPECT_EQ(counted.caustics.passes, 7);
  EXPECT_FALSE(passesUntilBudget(counted.caustics));
  const SceneDescription none = parse("caustics:\n  time_budget: 0\n");
  EXPECT_FALSE(none.caustics.progressive);
  EXPECT_EQ(none.caustics.passes, CausticSettings{}.passes);
}

TEST(YamlSceneParser, CausticsDefaultToNone) {
  const SceneDescription s = parse("objects:\n  - sphere: {center: [0, 0, 0], radius: 1}\n");
  const CausticSettings defaults;
  EXPECT_EQ(s.caustics.method, CausticMethod::None);
  EXPECT_EQ(s.caustics.photons, defaults.photons);
  EXPECT_EQ(s.caustics.gather, defaults.gather);
  EXPECT_EQ(s.caustics.filter, PhotonFilter::Cone);
  EXPECT_FALSE(s.caustics.progressive);
  EXPECT_FLOAT_EQ(s.caustics.alpha, 0.7f);
  EXPECT_EQ(s.spheres[0].caustic, CausticRole::Auto);
}

TEST(YamlSceneParser, EveryCausticRoleAndFilterParses) {
  const std::pair<const char*, CausticRole> roles[] = {{"auto", CausticRole::Auto},
                                                       {"cast", CausticRole::Cast},
                                                       {"receive", CausticRole::Receive},
                                                       {"both", CausticRole::Both},
                                                       {"off", CausticRole::Off}};
  for (const auto& [name, role] : roles) {
    const SceneDescription s = parse(
        std::string("objects:\n  - plane: {point: [0, 0, 0], normal: [0, 1, 0], caustic: ") + name +
        "}\n  - cylinder: {base: [0, 0, 0], apex: [0, 1, 0], radius: 1, caustic: " + name +
        "}\n  - mesh: {file: ../meshes/quad.obj, caustic: " + name + "}\n");
    EXPECT_EQ(s.planes[0].caustic, role) << name;
    EXPECT_EQ(s.cones[0].caustic, role) << name;
    EXPECT_EQ(s.meshes[0].caustic, role) << name;
  }
  const std::pair<const char*, PhotonFilter> filters[] = {
      {"box", PhotonFilter::Box},
      {"cone", PhotonFilter::Cone},
      {"epanechnikov", PhotonFilter::Epanechnikov}};
  for (const auto& [name, filter] : filters) {
    EXPECT_EQ(parse(std::string("caustics: {filter: ") + name + "}\n").caustics.filter, filter);
  }
  EXPECT_EQ(parse("caustics: {method: none}\n").caustics.method, CausticMethod::None);
  // alpha just inside its open interval, and an explicit zero radius (automatic)
  const SceneDescription s = parse("caustics: {alpha: 0.001, radius: 0, max_radius: 0}\n");
  EXPECT_FLOAT_EQ(s.caustics.alpha, 0.001f);
  EXPECT_EQ(s.caustics.radius, 0.0f);
}

// Named values follow scene/SettingNames.h: '-' and '_' alike, any case, so a value copied from
// the command line works in a scene file.
TEST(YamlSceneParser, NamedValuesAcceptEitherSpelling) {
  for (const char* method : {"photon_map", "photon-map", "Photon_Map"}) {
    EXPECT_EQ(parse(std::string("caustics: {method: ") + method + "}").caustics.method,
              CausticMethod::PhotonMap)
        << method;
  }
  EXPECT_EQ(parse("caustics: {method: map}").caustics.method, CausticMethod::CausticMap);
  for (const char* test : {"plane_inside", "plane-inside"}) {
    EXPECT_EQ(parse(std::string("render: {triangle_test: ") + test + "}").render.triangleTest,
              TriangleTest::PlaneThenInside)
        << test;
  }
  EXPECT_EQ(parse("render: {triangle_test: watertight}").render.triangleTest,
            TriangleTest::Watertight);
  EXPECT_EQ(parse("caustics: {map_paths: front-face}").caustics.mapPaths,
            CausticMapPaths::FrontFace);
  EXPECT_NE(std::string(parseError("render: {triangle_test: pluecker}").what())
                .find("(expected moller_trumbore, plane_inside or watertight)"),
            std::string::npos);
}

// Integer settings share their ranges with the command line and the codec (SettingLimits.h).
TEST(YamlSceneParser, IntegerSettingsHaveTheCommandLinesRanges) {
  EXPECT_EQ(parse("render: {max_depth: 256}").render.maxDepth, 256);
  EXPECT_EQ(parseError("render: {max_depth: 257}").message(),
            "'max_depth' must be at most 256, found 257");
  EXPECT_EQ(parseError("render: {samples: 65537}").message(),
            "'samples' must be at most 65536, found 65537");
  EXPECT_EQ(parseError("render: {width: 1048577}").message(),
            "'width' must be at most 1048576, found 1048577");
  EXPECT_EQ(parseError("caustics: {passes: 1048577}").message(),
            "'passes' must be at most 1048576, found 1048577");
}

TEST(YamlSceneParser, ColoursAreScalarsOrTriples) {
  const SceneDescription s = parse(R"(
materials:
  - {name: grey, diffuse: 0.25, specular: 1e-1, reflectance: [0, 0.5, 1]}
  - {name: integers, diffuse: 1, ambient: [1, 0, 0]}
)");
  ASSERT_EQ(s.materials.size(), 2u);
  expectVec(s.materials[0].diffuse, Color(0.25f));
  expectVec(s.materials[0].specular, Color(0.1f));
  expectVec(s.materials[0].reflectance, {0, 0.5f, 1});
  expectVec(s.materials[1].diffuse, Color(1.0f));
  expectVec(s.materials[1].ambient, {1, 0, 0});
}

TEST(YamlSceneParser, NumbersFollowYamlFloatSyntax) {
  const SceneDescription s = parse(R"(
lights:
  - {position: [+1.5, -.5, 2E2], intensity: 1.}
)");
  expectVec(s.lights[0].position, {1.5f, -0.5f, 200.0f});
  expectVec(s.lights[0].intensity, Color(1.0f));
}

TEST(YamlSceneParser, CylinderIsAConeWithEqualRadii) {
  const SceneDescription s = parse(R"(
objects:
  - cylinder: {base: [0, 0, 0], apex: [0, 2, 0], radius: 0.5}
)");
  ASSERT_EQ(s.cones.size(), 1u);
  expectVec(s.cones[0].base, {0, 0, 0});
  expectVec(s.cones[0].apex, {0, 2, 0});
  EXPECT_EQ(s.cones[0].baseRadius, 0.5f);
  EXPECT_EQ(s.cones[0].apexRadius, 0.5f);
}

TEST(YamlSceneParser, DiscHasAUnitNormalAndTheObjectsCommonKeys) {
  const SceneDescription s = parse(R"(
materials:
  - {name: mirror, reflectance: 1}
objects:
  - disc: {center: [1, 2, 3], normal: [0, 0, 2], radius: 0.5, material: mirror, caustic: cast}
)");
  ASSERT_EQ(s.discs.size(), 1u);
  expectVec(s.discs[0].center, {1, 2, 3});
  expectVec(s.discs[0].normal, {0, 0, 1});
  EXPECT_EQ(s.discs[0].radius, 0.5f);
  EXPECT_EQ(s.discs[0].material, 0u);
  EXPECT_EQ(s.discs[0].caustic, CausticRole::Cast);
  EXPECT_EQ(s.discs[0].loc.line, 5);
}

TEST(YamlSceneParser, TriangleIsAOneTriangleMeshWithNormalisedNormals) {
  const SceneDescription s = parse(R"(
objects:
  - triangle:
      vertices: [[0, 0, 0], [1, 0, 0], [0, 1, 0]]
      normals: [[0, 0, 3], [0, 3, 0], [3, 0, 0]]
)");
  ASSERT_EQ(s.meshes.size(), 1u);
  const MeshDesc& m = s.meshes[0];
  EXPECT_EQ(m.source, "triangle");
  ASSERT_EQ(m.positions.size(), 3u);
  expectVec(m.positions[1], {1, 0, 0});
  ASSERT_EQ(m.normals.size(), 3u);
  expectVec(m.normals[0], {0, 0, 1});
  expectVec(m.normals[1], {0, 1, 0});
  expectVec(m.normals[2], {1, 0, 0});
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2}));
  EXPECT_EQ(m.loc.line, 4);
  EXPECT_EQ(m.loc.column, 7);
}

TEST(YamlSceneParser, TriangleWithoutNormalsIsFlat) {
  const SceneDescription s = parse(R"(
objects:
  - triangle: {vertices: [[0, 0, 0], [1, 0, 0], [0, 1, 0]]}
)");
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_TRUE(s.meshes[0].normals.empty());
}

// The transform is checked against the same file loaded untransformed, vertex by vertex, so the
// test does not depend on how the OBJ loader orders vertices.
TEST(YamlSceneParser, MeshTransformScalesThenRotatesXYZThenTranslates) {
  const SceneDescription plain = parse("objects: [mesh: {file: ../meshes/quad.obj}]");
  const SceneDescription moved = parse(R"(
objects:
  - mesh:
      file: ../meshes/quad.obj
      transform: {scale: [2, 1, 1], rotate: [90, 0, 90], translate: [0, 0, 5]}
)");
  ASSERT_EQ(plain.meshes.size(), 1u);
  ASSERT_EQ(moved.meshes.size(), 1u);
  const MeshDesc& a = plain.meshes[0];
  const MeshDesc& b = moved.meshes[0];
  ASSERT_EQ(a.triangleCount(), 2u);
  ASSERT_EQ(a.positions.size(), b.positions.size());
  ASSERT_EQ(a.normals.size(), a.positions.size());
  ASSERT_EQ(b.normals.size(), b.positions.size());
  EXPECT_EQ(a.indices, b.indices);
  // Scale x by 2; rotate 90° about X: (x, y, z) -> (x, -z, y); then about Z: (x, y, z) ->
  // (-y, x, z); then add 5 to z. So (x, y, 0) -> (0, 2x, y + 5). Rotating about Z first would
  // give (-y, 0, 2x + 5) instead.
  for (size_t i = 0; i < a.positions.size(); ++i) {
    const Vec3 p = a.positions[i];
    expectVec(b.positions[i], {0.0f, 2.0f * p.x, p.y + 5.0f}, 1e-5f);
    expectVec(b.normals[i], {1, 0, 0}, 1e-6f);  // +Z -> -Y (about X) -> +X (about Z)
  }
}

// A glTF placed by a scene brings its materials and textures; its camera and lights only when
// asked, moved by the mesh's transform. scenes/globe.glb holds one camera (at (0, 0.4, 4.2))
// and one light.
TEST(YamlSceneParser, AModelsCameraAndLightsComeWhenAskedAndMoveWithIt) {
  const std::string globe = std::string(PRISM_SOURCE_DIR) + "/scenes/globe.glb";
  const SceneDescription plain = parse("objects: [mesh: {file: " + globe + "}]");
  EXPECT_TRUE(plain.lights.empty());
  EXPECT_EQ(plain.camera.position, CameraDesc{}.position);
  ASSERT_EQ(plain.meshes.size(), 2u);
  EXPECT_EQ(plain.materials.size(), 2u);  // the globe's map and the brass
  EXPECT_EQ(plain.textures.size(), 1u);
  const SceneDescription asked = parse("objects: [mesh: {file: " + globe +
                                       ", camera: true, lights: true, transform: {translate: "
                                       "[10, 0, 0]}}]");
  ASSERT_EQ(asked.lights.size(), 1u);
  expectVec(asked.camera.position, {10.0f, 0.4f, 4.2f}, 1e-5f);
  expectVec(asked.lights[0].position, {7.0f, 3.0f, 3.0f}, 1e-5f);
  // A scene material replaces the model's for every face.
  const SceneDescription grey = parse(R"(
materials: [{name: grey, diffuse: 0.5}]
objects: [mesh: {file: )" + globe + R"(, material: grey}]
)");
  EXPECT_EQ(grey.materials.size(), 1u);
  EXPECT_TRUE(grey.textures.empty());
  try {
    parse("objects: [mesh: {file: ../meshes/quad.obj, camera: true}]");
    ADD_FAILURE() << "a camera taken from a file without one";
  } catch (const SceneError& e) {
    EXPECT_NE(e.message().find("has no camera to take"), std::string::npos) << e.what();
  }
}

// quad.ply holds quad.obj's square as one polygon, which the PLY reader splits into the same fan.
TEST(YamlSceneParser, PlyMeshesLoadLikeObjMeshes) {
  const SceneDescription obj = parse("objects: [mesh: {file: ../meshes/quad.obj}]");
  const SceneDescription ply = parse("objects: [mesh: {file: ../meshes/quad.ply}]");
  ASSERT_EQ(ply.meshes.size(), 1u);
  EXPECT_EQ(ply.meshes[0].positions, obj.meshes[0].positions);
  EXPECT_EQ(ply.meshes[0].normals, obj.meshes[0].normals);
  EXPECT_EQ(ply.meshes[0].indices, obj.meshes[0].indices);
}

// slope.obj is one triangle in the plane x + y = 1 with normal (1, 1, 0)/√2. Stretched 2x along
// X the plane becomes x/2 + y = 1, whose normal is ∝ (1/2, 1, 0): what the inverse transpose
// gives, and not what transforming the normal like a position (∝ (2, 1, 0)) would.
TEST(YamlSceneParser, MeshNormalsFollowTheInverseTranspose) {
  const SceneDescription s = parse(R"(
objects:
  - mesh: {file: ../meshes/slope.obj, transform: {scale: [2, 1, 1], rotate: [0, 0, 30]}}
  - mesh: {file: ../meshes/slope.obj, transform: {scale: 3}}
)");
  ASSERT_EQ(s.meshes.size(), 2u);
  const MeshDesc& stretched = s.meshes[0];
  const float c = std::cos(glm::radians(30.0f)), sn = std::sin(glm::radians(30.0f));
  const Vec3 n = glm::normalize(Vec3(0.5f, 1.0f, 0.0f));
  const Vec3 rotated(c * n.x - sn * n.y, sn * n.x + c * n.y, 0.0f);
  ASSERT_EQ(stretched.normals.size(), stretched.positions.size());
  for (const Vec3& normal : stretched.normals) expectVec(normal, rotated, 1e-6f);
  // Whatever the transform, the normal stays perpendicular to the surface.
  const Vec3& p0 = stretched.positions[stretched.indices[0]];
  const Vec3& p1 = stretched.positions[stretched.indices[1]];
  const Vec3& p2 = stretched.positions[stretched.indices[2]];
  EXPECT_NEAR(glm::dot(p1 - p0, stretched.normals[0]), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(p2 - p0, stretched.normals[0]), 0.0f, 1e-6f);

  // A uniform scale moves the vertices and leaves unit normals as they were.
  const MeshDesc& uniform = s.meshes[1];
  for (const Vec3& normal : uniform.normals)
    expectVec(normal, {std::sqrt(0.5f), std::sqrt(0.5f), 0});
  float maxX = 0.0f;
  for (const Vec3& p : uniform.positions) maxX = std::max(maxX, p.x);
  EXPECT_FLOAT_EQ(maxX, 3.0f);
}

TEST(YamlSceneParser, MirroringScaleRewindsTriangles) {
  const SceneDescription plain = parse("objects: [mesh: {file: ../meshes/quad.obj}]");
  const SceneDescription mirrored =
      parse("objects: [mesh: {file: ../meshes/quad.obj, transform: {scale: [-1, 1, 1]}}]");
  const MeshDesc& a = plain.meshes[0];
  const MeshDesc& b = mirrored.meshes[0];
  ASSERT_EQ(a.indices.size(), b.indices.size());
  for (size_t t = 0; t < a.triangleCount(); ++t) {
    EXPECT_EQ(b.indices[3 * t], a.indices[3 * t]);
    EXPECT_EQ(b.indices[3 * t + 1], a.indices[3 * t + 2]);
    EXPECT_EQ(b.indices[3 * t + 2], a.indices[3 * t + 1]);
    // The winding's normal still agrees with the vertex normal.
    const Vec3 p0 = b.positions[b.indices[3 * t]];
    const Vec3 p1 = b.positions[b.indices[3 * t + 1]];
    const Vec3 p2 = b.positions[b.indices[3 * t + 2]];
    EXPECT_GT(glm::dot(glm::cross(p1 - p0, p2 - p0), b.normals[b.indices[3 * t]]), 0.0f);
  }
}

TEST(YamlSceneParser, DefaultMaterialIsAddedOnlyWhenUsed) {
  const SceneDescription named = parse(R"(
materials: [{name: red, diffuse: [1, 0, 0]}, {name: unused}]
objects: [sphere: {center: [0, 0, 0], radius: 1, material: red}]
)");
  ASSERT_EQ(named.materials.size(), 2u);
  EXPECT_EQ(named.materials[0].name, "red");
  EXPECT_EQ(named.materials[1].name, "unused");

  const SceneDescription mixed = parse(R"(
objects:
  - sphere: {center: [0, 0, 0], radius: 1}
  - sphere: {center: [3, 0, 0], radius: 1, material: red}
  - sphere: {center: [6, 0, 0], radius: 1, material: default}
materials: [{name: red}]
)");
  ASSERT_EQ(mixed.materials.size(), 2u);
  EXPECT_EQ(mixed.materials[1].name, "default");
  EXPECT_EQ(mixed.spheres[0].material, 1u);
  EXPECT_EQ(mixed.spheres[1].material, 0u);  // defined after the objects: still found
  EXPECT_EQ(mixed.spheres[2].material, 1u);  // named explicitly: the same built-in one
}

TEST(YamlSceneParser, SceneMayDefineItsOwnDefaultMaterial) {
  const SceneDescription s = parse(R"(
materials: [{name: default, diffuse: 0.1}]
objects: [plane: {point: [0, 0, 0], normal: [0, 0, 1]}]
)");
  ASSERT_EQ(s.materials.size(), 1u);
  expectVec(s.materials[0].diffuse, Color(0.1f));
  EXPECT_EQ(s.planes[0].material, 0u);
}

TEST(YamlSceneParser, EmptySectionsTakeDefaults) {
  const SceneDescription s = parse("camera:\nrender:\nmaterials:\nlights:\nobjects:\n");
  EXPECT_EQ(s.render.width, RenderSettings().width);
  EXPECT_TRUE(s.materials.empty());
  EXPECT_TRUE(s.lights.empty());
}

TEST(YamlSceneParser, AnchorsAndAliasesWork) {
  const SceneDescription s = parse(R"(
materials:
  - {name: a, diffuse: &warm [0.9, 0.6, 0.3]}
  - {name: b, specular: *warm}
)");
  expectVec(s.materials[1].specular, {0.9f, 0.6f, 0.3f});
}

TEST(YamlSceneParser, ErrorTextIsFileLineColumnMessage) {
  const SceneError e = parseError("objects:\n  - sphere: {center: [0, 0, 0], radius: 0}\n");
  EXPECT_EQ(e.loc().file, dataPath("scenes/inline.yaml"));
  EXPECT_EQ(std::string(e.what()),
            dataPath("scenes/inline.yaml") + ":2:41: 'radius' must be greater than 0, found 0");
}

// The faces are read at once; whichever finishes first, the error names the first failing face in
// the file's order, at its line.
TEST(YamlSceneParser, TheFirstUnreadableCubeMapFaceInOrderIsReported) {
  const std::string sky = "../../../scenes/assets/sky/";
  for (int run = 0; run < 5; ++run) {
    const SceneError e =
        parseError("environment:\n  cubemap:\n    px: " + sky + "px.png\n    nx: " + sky +
                   "nx.png\n    py: " + sky + "py.png\n    ny: missing-ny.png\n" +
                   "    pz: " + sky + "pz.png\n    nz: missing-nz.png\n");
    EXPECT_EQ(e.loc().line, 6);
    EXPECT_NE(e.message().find("cube-map face 'ny': cannot read image"), std::string::npos)
        << e.message();
  }
  const SceneDescription s =
      parse("environment:\n  cubemap: {px: " + sky + "px.png, nx: " + sky + "nx.png, py: " + sky +
            "py.png, ny: " + sky + "ny.png, pz: " + sky + "pz.png, nz: " + sky + "nz.png}\n");
  ASSERT_TRUE(s.environment.has_value());
  const char* names[] = {"px", "nx", "py", "ny", "pz", "nz"};
  for (size_t i = 0; i < 6; ++i) {  // each face is its own file's pixels, in its own slot
    // 8-bit PNG faces are kept as their bytes, which decode to what readImage gives.
    const std::string file = dataPath("scenes/" + sky + names[i] + ".png");
    const std::optional<SrgbImage> bytes = readSrgbImage(file);
    ASSERT_TRUE(bytes) << names[i];
    EXPECT_GT(bytes->width, 0);
    EXPECT_TRUE(s.environment->faces[i].pixels.empty()) << names[i];
    EXPECT_EQ(s.environment->srgbFaces[i].rgb, bytes->rgb) << names[i];
    EXPECT_TRUE(linearFromSrgb(s.environment->srgbFaces[i]).pixels == readImage(file).pixels)
        << names[i];
  }
}

TEST(YamlSceneParser, UnknownMaterialWithNoneDefined) {
  const SceneError e = parseError("objects: [sphere: {center: [0, 0, 0], radius: 1, material: x}]");
  EXPECT_EQ(e.message(), "unknown material 'x' (no materials are defined)");
}

TEST(YamlSceneParser, ControlBytesInMessagesAreEscaped) {
  const SceneError e = parseError("camera: {projection: \"fish\\x07eye\"}");
  EXPECT_NE(e.message().find("'fish\\x07eye'"), std::string::npos) << e.message();
}

// ---- environment --------------------------------------------------------------------------

class YamlEnvironment : public YamlSceneFiles {
 protected:
  // Writes six EXR faces of the given sizes, face i filled with radiance i + 1.
  void writeFaces(const std::array<int, 6>& sizes, int height = 0) {
    const char* names[] = {"px", "nx", "py", "ny", "pz", "nz"};
    fs::create_directories(dir_ / "sky");
    for (int i = 0; i < 6; ++i) {
      ImageRgb face(sizes[i], height > 0 ? height : sizes[i]);
      for (Color& c : face.pixels) c = Color(static_cast<float>(i + 1));
      writeImage(face, (dir_ / "sky" / (std::string(names[i]) + ".exr")).string());
    }
  }

  static constexpr const char* kScene = R"(environment:
  scale: 2
  cubemap: {px: sky/px.exr, nx: sky/nx.exr, py: sky/py.exr,
            ny: sky/ny.exr, pz: sky/pz.exr, nz: sky/nz.exr}
)";
};

TEST_F(YamlEnvironment, LoadsSixFacesInOpenGlOrder) {
  writeFaces({4, 4, 4, 4, 4, 4});
  const std::string path = write("scene.yaml", kScene);
  const SceneDescription s = parseYamlScene(readTextFile(path), path);
  ASSERT_TRUE(s.environment);
  EXPECT_FLOAT_EQ(s.environment->scale, 2.0f);
  for (int i = 0; i < 6; ++i) {
    ASSERT_EQ(s.environment->faces[i].width, 4);
    expectVec(s.environment->faces[i].at(1, 2), Color(static_cast<float>(i + 1)));
  }
  EXPECT_EQ(s.environment->paths[0], "sky/px.exr");
  EXPECT_EQ(s.environment->paths[5], "sky/nz.exr");
}

TEST_F(YamlEnvironment, AFloatFaceAmongPngFacesMakesThemAllRadiance) {
  // Five 8-bit PNG faces and one EXR: all six become radiance, the PNGs decoded as readImage
  // decodes them.
  writeFaces({4, 4, 4, 4, 4, 4});
  const char* names[] = {"px", "nx", "py", "ny", "pz"};
  for (const char* name : names) {
    ImageRgb face(4, 4);
    for (Color& c : face.pixels) c = Color(0.2f, 0.5f, 0.9f);
    writeImage(face, (dir_ / "sky" / (std::string(name) + ".png")).string());
  }
  const std::string path = write("scene.yaml", R"(environment:
  cubemap: {px: sky/px.png, nx: sky/nx.png, py: sky/py.png,
            ny: sky/ny.png, pz: sky/pz.png, nz: sky/nz.exr}
)");
  const SceneDescription s = parseYamlScene(readTextFile(path), path);
  ASSERT_TRUE(s.environment);
  EXPECT_FALSE(s.environment->keptAsBytes());
  for (int i = 0; i < 6; ++i) {
    EXPECT_TRUE(s.environment->srgbFaces[i].empty()) << i;
    const std::string file =
        (dir_ / "sky" / (i < 5 ? std::string(names[i]) + ".png" : "nz.exr")).string();
    EXPECT_TRUE(s.environment->faces[i].pixels == readImage(file).pixels) << i;
  }
}

TEST_F(YamlEnvironment, FacesMustBeSquareAndAlike) {
  writeFaces({4, 4, 4, 8, 4, 4});
  const std::string path = write("scene.yaml", kScene);
  try {
    parseYamlScene(readTextFile(path), path);
    FAIL() << "faces of different sizes were accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.loc().line, 4);
    EXPECT_EQ(e.loc().column, 17);  // ny's value
    EXPECT_NE(e.message().find("same size"), std::string::npos) << e.what();
  }
  writeFaces({4, 4, 4, 4, 4, 4}, 2);
  try {
    parseYamlScene(readTextFile(path), path);
    FAIL() << "non-square faces were accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.loc().line, 3);
    EXPECT_EQ(e.loc().column, 17);  // px's value
    EXPECT_NE(e.message().find("must be square"), std::string::npos) << e.what();
  }
}

// ---- malformed scenes ---------------------------------------------------------------------

struct BadScene {
  const char* file;  // in tests/data/bad
  int line;          // 0: the error names only the file
  int column;
  const char* fragment;  // part of the message
};

std::ostream& operator<<(std::ostream& out, const BadScene& b) {
  return out << b.file;
}

class YamlBadScene : public testing::TestWithParam<BadScene> {};

TEST_P(YamlBadScene, ReportsLineColumnAndWhatIsWrong) {
  const BadScene& bad = GetParam();
  const std::string path = dataPath(std::string("bad/") + bad.file);
  ASSERT_TRUE(fs::exists(path)) << path;
  try {
    loadScene(path);
    FAIL() << bad.file << " loaded without an error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.loc().file, path);
    EXPECT_EQ(e.loc().line, bad.line) << e.what();
    EXPECT_EQ(e.loc().column, bad.column) << e.what();
    EXPECT_NE(e.message().find(bad.fragment), std::string::npos)
        << "message: " << e.message() << "\nexpected to contain: " << bad.fragment;
    EXPECT_EQ(std::string(e.what()), e.loc().toString() + ": " + e.message());
  }
}

const BadScene kBadScenes[] = {
    // YAML itself
    {"truncated.yaml", 5, 1, "invalid YAML: end of map flow not found"},
    {"binary_garbage.yaml", 3, 3, "invalid YAML"},
    {"tab_indentation.yaml", 2, 5, "invalid YAML"},
    {"two_documents.yaml", 2, 1, "expected one YAML document"},
    {"empty.yaml", 0, 0, "scene is empty"},
    {"top_level_list.yaml", 1, 1, "expected a mapping of scene sections"},
    {"duplicate_key.yaml", 2, 44, "duplicate key 'radius' (first given at 2:33)"},
    // keys
    {"unknown_key.yaml", 3, 3, "unknown camera key 'fvo' (expected one of: projection, position"},
    {"unknown_top_level_key.yaml", 2, 1, "unknown top-level key 'lightz'"},
    {"missing_radius.yaml", 2, 13, "sphere needs 'radius'"},
    {"missing_light_position.yaml", 2, 5, "light needs 'position'"},
    {"missing_cubemap_face.yaml", 2, 12, "cubemap needs 'nz'"},
    {"section_wrong_type.yaml", 1, 9, "expected a mapping of camera keys"},
    // objects
    {"two_kinds_in_one_entry.yaml", 3, 5, "an object entry holds exactly one object"},
    {"unknown_object_kind.yaml", 2, 5, "unknown object kind 'box'"},
    {"object_not_mapping.yaml", 2, 5, "expected an object such as 'sphere: {...}'"},
    // types
    {"wrong_type_number.yaml", 2, 41, "expected a number for 'radius', found 'abc'"},
    {"quoted_number.yaml", 2, 41, "found the quoted string '1'"},
    {"wrong_type_vector.yaml", 3, 15,
     "expected a list of 3 numbers for 'center', found a list of 2"},
    {"empty_value.yaml", 3, 7, "expected a list of 3 numbers for 'center', found nothing"},
    {"triangle_two_vertices.yaml", 3, 17, "expected a list of 3 points for 'vertices'"},
    {"width_not_integer.yaml", 2, 10, "expected an integer for 'width', found '640.5'"},
    {"bad_bool.yaml", 3, 14, "expected true or false for 'fresnel', found 'maybe'"},
    {"bad_projection.yaml", 2, 15,
     "unknown projection 'fisheye' (expected perspective or orthographic)"},
    {"bad_triangle_test.yaml", 2, 18, "unknown triangle_test 'pluecker'"},
    // values
    {"nan_radius.yaml", 3, 41, "'radius' must be finite, found '.nan'"},
    {"infinite_position.yaml", 2, 19, "'position' must be finite, found '-.inf'"},
    {"negative_radius.yaml", 2, 41, "'radius' must be greater than 0, found -1"},
    {"ior_below_one.yaml", 4, 10, "'ior' must be at least 1, found 0.9"},
    {"negative_color.yaml", 3, 20, "'diffuse' must not be negative, found -0.1"},
    {"negative_intensity.yaml", 3, 16, "'intensity' must not be negative, found -100"},
    {"zero_attenuation.yaml", 3, 18, "infinitely bright"},
    {"zero_normal.yaml", 2, 39, "'normal' must not be the zero vector"},
    {"cone_without_axis.yaml", 2, 51, "'apex' must differ from 'base'"},
    {"disc_zero_radius.yaml", 2, 58, "'radius' must be greater than 0, found 0"},
    {"disc_without_normal.yaml", 2, 11, "disc needs 'normal'"},
    {"mesh_zero_scale.yaml", 5, 16, "'scale' must not be zero"},
    {"fov_zero.yaml", 2, 8, "'fov' must be between 0 and 180 degrees (exclusive), found 0"},
    {"fov_180.yaml", 1, 15, "'fov' must be between 0 and 180"},
    {"samples_zero.yaml", 4, 12, "'samples' must be at least 1, found 0"},
    {"height_negative.yaml", 2, 11, "'height' must be at least 1, found -360"},
    {"max_depth_negative.yaml", 2, 14, "'max_depth' must be at least 0, found -1"},
    {"negative_seed.yaml", 2, 9, "'seed' must not be negative"},
    {"camera_same_point.yaml", 3, 12, "'position' and 'look_at' are the same point"},
    // caustics
    {"unknown_caustic_method.yaml", 2, 11,
     "unknown method 'photons' (expected none, photon_map or caustic_map)"},
    {"unknown_photon_filter.yaml", 2, 11,
     "unknown filter 'gaussian' (expected box, cone or epanechnikov)"},
    {"unknown_caustic_role.yaml", 2, 53,
     "unknown caustic 'emit' (expected auto, cast, receive, both or off)"},
    {"unknown_caustics_key.yaml", 2, 3, "unknown caustics key 'photon_count'"},
    {"alpha_out_of_range.yaml", 3, 10, "'alpha' must lie strictly between 0 and 1, found 1.5"},
    {"photons_zero.yaml", 2, 12, "'photons' must be at least 1"},
    {"gather_zero.yaml", 2, 11, "'gather' must be at least 1, found 0"},
    {"gather_not_auto.yaml", 2, 11, "expected an integer for 'gather', found 'automatic'"},
    {"noise_too_large.yaml", 3, 10, "'noise' must lie between 0.0032 and 1, found 2"},
    {"negative_time_budget.yaml", 2, 16, "'time_budget' must not be negative, found -1"},
    {"budget_without_progressive.yaml", 2, 16,
     "'progressive' is false, but 'time_budget' bounds progressive passes: remove one of them"},
    {"up_parallel.yaml", 1, 1, "'up' is parallel to the view direction"},
    // references
    {"unknown_material.yaml", 5, 54, "unknown material 'glas' (defined: floor, glass)"},
    {"duplicate_material.yaml", 4, 11, "duplicate material 'floor' (first defined at "},
    {"missing_mesh_file.yaml", 3, 13, "mesh file '../meshes/does_not_exist.obj' not found"},
    {"unreadable_cubemap_face.yaml", 3, 9, "cube-map face 'px': cannot read image"},
};

INSTANTIATE_TEST_SUITE_P(Yaml, YamlBadScene, testing::ValuesIn(kBadScenes),
                         [](const testing::TestParamInfo<BadScene>& info) {
                           std::string name = info.param.file;
                           name = name.substr(0, name.find('.'));
                           return name;
                         });

TEST(YamlBadScenes, EveryFileInTheFolderIsInTheTable) {
  for (const auto& entry : fs::directory_iterator(dataPath("bad"))) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".yaml") continue;
    const bool listed = std::any_of(std::begin(kBadScenes), std::end(kBadScenes),
                                    [&](const BadScene& b) { return name == b.file; });
    EXPECT_TRUE(listed) << name << " is not checked by the table";
  }
}

// ---- robustness ---------------------------------------------------------------------------

// Whatever the bytes, parsing ends in a scene or a SceneError: never a crash, a hang or another
// exception. (yaml-cpp 0.7 alone loops, allocating without bound, on a lone ','.)
void expectParsesOrSceneError(const std::string& text) {
  try {
    parse(text);
  } catch (const SceneError& e) {
    EXPECT_FALSE(e.message().empty());
  }
}

TEST(YamlSceneParserRobustness, RandomBytes) {
  std::mt19937 rng(20240611);
  for (int i = 0; i < 500; ++i) {
    std::string text(rng() % 300, '\0');
    for (char& c : text) c = static_cast<char>(rng());
    expectParsesOrSceneError(text);
  }
}

TEST(YamlSceneParserRobustness, MutatedScene) {
  const std::string base = readTextFile(dataPath("scenes/full.yaml"));
  const std::string alphabet = "{}[]:-,&*!|>'\"#%@` \n\t0123456789.eE+-abcxyz";
  std::mt19937 rng(7);
  for (int i = 0; i < 500; ++i) {
    std::string text = base;
    for (int k = 0, n = 1 + static_cast<int>(rng() % 4); k < n; ++k) {
      const size_t pos = rng() % text.size();
      const char c = alphabet[rng() % alphabet.size()];
      switch (rng() % 3) {
        case 0:
          text[pos] = c;
          break;
        case 1:
          text.erase(pos, 1 + rng() % 5);
          break;
        default:
          text.insert(pos, 1, c);
      }
    }
    expectParsesOrSceneError(text);
  }
}

TEST(YamlSceneParserRobustness, PathologicalInputs) {
  const std::string inputs[] = {
      ",",
      " ,",
      ",a",
      std::string(100000, '['),
      std::string(100000, '{'),
      "a: &x [*x, *x]\n",
      "objects: &x [*x]\n",
      "materials: &x [{name: a, diffuse: *x}]\n",
      std::string("camera:\0 {}", 11),
      "\xef\xbb\xbf"
      "camera: {}",    // a UTF-8 byte-order mark
      "? [a]\n: 1\n",  // a key that is not a name
  };
  for (const std::string& text : inputs) expectParsesOrSceneError(text);
  EXPECT_EQ(parseError(",").message(), "invalid YAML: unexpected ','");
  EXPECT_NE(parseError(std::string(5000, '[')).message().find("invalid YAML"), std::string::npos);
}

// ---- documentation ------------------------------------------------------------------------

std::string docText() {
  return readTextFile(PRISM_SOURCE_DIR "/docs/scene-format.md");
}

// The body of the section whose heading reads `name` (backticks and case aside), up to the next
// heading of the same or a higher level.
std::string docSection(const std::string& doc, const std::string& name) {
  std::istringstream lines(doc);
  std::string line, body;
  size_t level = 0;
  bool inCode = false;  // a '#' comment in a code block is not a heading
  while (std::getline(lines, line)) {
    if (line.rfind("```", 0) == 0) inCode = !inCode;
    const size_t hashes = line.find_first_not_of('#');
    const bool heading =
        !inCode && hashes != std::string::npos && hashes > 0 && line[hashes] == ' ';
    if (level > 0) {
      if (heading && hashes <= level) break;
      body += line + "\n";
    } else if (heading) {
      std::string title = line.substr(hashes + 1);
      title.erase(std::remove(title.begin(), title.end(), '`'), title.end());
      std::transform(title.begin(), title.end(), title.begin(),
                     [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
      if (title == name) level = hashes;
    }
  }
  return body;
}

TEST(YamlSceneDocs, EveryAcceptedKeyIsDocumentedInItsSection) {
  const std::string doc = docText();
  ASSERT_FALSE(yamlSceneKeys().empty());
  for (const auto& [section, keys] : yamlSceneKeys()) {
    const std::string body = docSection(doc, section);
    ASSERT_FALSE(body.empty()) << "docs/scene-format.md has no section '" << section << "'";
    for (const std::string& key : keys) {
      EXPECT_NE(body.find("| `" + key + "` |"), std::string::npos)
          << "key '" << key << "' of section '" << section
          << "' is not a row of that section's table in docs/scene-format.md";
    }
  }
}

// The complete example in the reference must stay a valid scene. Its mesh and cube-map faces are
// made up here: quad.obj stands in for the mesh, tiny images for the faces.
TEST_F(YamlSceneFiles, DocumentationExampleParses) {
  const std::string body = docSection(docText(), "complete example");
  const size_t start = body.find("```yaml\n");
  ASSERT_NE(start, std::string::npos);
  const size_t end = body.find("```", start + 8);
  const std::string example = body.substr(start + 8, end - start - 8);

  const std::regex meshFile(R"(file: (\S+))");
  for (auto it = std::sregex_iterator(example.begin(), example.end(), meshFile);
       it != std::sregex_iterator(); ++it) {
    write((*it)[1].str(), readTextFile(dataPath("meshes/quad.obj")));
  }
  const std::regex faceFile(R"((?:px|nx|py|ny|pz|nz): ([^,}\s]+))");
  for (auto it = std::sregex_iterator(example.begin(), example.end(), faceFile);
       it != std::sregex_iterator(); ++it) {
    const fs::path face = dir_ / (*it)[1].str();
    fs::create_directories(face.parent_path());
    writeImage(ImageRgb(2, 2), face.string());
  }
  const std::string path = write("example.yaml", example);
  const SceneDescription s = parseYamlScene(example, path);
  EXPECT_TRUE(s.environment);
  EXPECT_FALSE(s.spheres.empty());
  EXPECT_FALSE(s.meshes.empty());
  EXPECT_FALSE(s.lights.empty());
}

}  // namespace
}  // namespace prism
