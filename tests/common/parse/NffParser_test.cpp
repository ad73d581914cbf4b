#include "parse/NffParser.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "parse/PolygonTriangulator.h"

namespace prism {
namespace {

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in) << "cannot read " << path;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string nffPath(const std::string& name) {
  return PRISM_TEST_DATA_DIR "/nff/" + name;
}

float triangleArea(const MeshDesc& mesh, size_t t) {
  const Vec3& a = mesh.positions[mesh.indices[3 * t]];
  const Vec3& b = mesh.positions[mesh.indices[3 * t + 1]];
  const Vec3& c = mesh.positions[mesh.indices[3 * t + 2]];
  return 0.5f * glm::length(glm::cross(b - a, c - a));
}

void expectVec3Eq(const Vec3& actual, const Vec3& expected) {
  EXPECT_FLOAT_EQ(actual.x, expected.x);
  EXPECT_FLOAT_EQ(actual.y, expected.y);
  EXPECT_FLOAT_EQ(actual.z, expected.z);
}

// One statement of each kind, with values chosen so every mapping rule shows.
constexpr const char* kTinyScene = R"(# tiny scene
b 0.1 0.2 0.3
v
from 1 2 3
at 0 0 0
up 0 0 1
angle 40
hither 0.5
resolution 320 240
l 10 0 0
l 0 10 0 0.5 0.25 1   # coloured light
f 1 0.5 0.25 0.8 0.3 20 0 0
s 1 2 3 0.5
c
0 0 0 1
0 0 2 0.5
f 0.5 0.5 0.5 0.6 0.2 10 0.9 1.5
p 3
0 0 0
1 0 0
0 1 0
# a comment between polygons does not split the mesh
p 4
0 0 1  1 0 1  1 1 1  0 1 1
pp 3
0 0 2 0 0 2
1 0 2 0 0 1
0 1 2 0 0 1
s -1 -1 -1 -2
)";

TEST(NffParser, TinySceneMapsEveryStatement) {
  const SceneDescription scene = parseNff(kTinyScene, "tiny.nff");
  EXPECT_EQ(scene.sourcePath, "tiny.nff");

  expectVec3Eq(scene.background, Color(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(scene.ambientLight, Color(0.0f));

  const CameraDesc& camera = scene.camera;
  EXPECT_EQ(camera.projection, Projection::Perspective);
  expectVec3Eq(camera.position, Vec3(1, 2, 3));
  expectVec3Eq(camera.lookAt, Vec3(0, 0, 0));
  expectVec3Eq(camera.up, Vec3(0, 0, 1));
  EXPECT_FLOAT_EQ(camera.fovDegrees, 40.0f);
  EXPECT_FLOAT_EQ(camera.nearClip, 0.5f);
  EXPECT_EQ(camera.loc.line, 3);
  EXPECT_EQ(scene.render.width, 320);
  EXPECT_EQ(scene.render.height, 240);
  EXPECT_EQ(scene.render.maxDepth, 5);
  EXPECT_EQ(scene.render.samplesPerPixel, 1);

  // Two lights: each pi * sqrt(2) / 4 W/sr times its colour, no falloff.
  ASSERT_EQ(scene.lights.size(), 2u);
  const float unit = kPi * std::sqrt(2.0f) / 4.0f;
  expectVec3Eq(scene.lights[0].position, Vec3(10, 0, 0));
  expectVec3Eq(scene.lights[0].intensity, Color(unit));
  expectVec3Eq(scene.lights[1].intensity, unit * Color(0.5f, 0.25f, 1.0f));
  for (const PointLightDesc& light : scene.lights) {
    EXPECT_EQ(light.attenuation.constant, 1.0f);
    EXPECT_EQ(light.attenuation.linear, 0.0f);
    EXPECT_EQ(light.attenuation.quadratic, 0.0f);
  }
  EXPECT_EQ(scene.lights[1].loc.line, 11);
  EXPECT_EQ(scene.lights[1].loc.column, 1);

  ASSERT_EQ(scene.materials.size(), 2u);
  const MaterialDesc& opaque = scene.materials[0];
  EXPECT_EQ(opaque.name, "f1");
  EXPECT_EQ(opaque.loc.line, 12);
  expectVec3Eq(opaque.diffuse, Color(0.8f, 0.4f, 0.2f));
  expectVec3Eq(opaque.specular, Color(0.3f / kPi));
  EXPECT_FLOAT_EQ(opaque.shininess, 20.0f);
  expectVec3Eq(opaque.reflectance, Color(0.3f));
  expectVec3Eq(opaque.transmittance, Color(0.0f));
  EXPECT_FLOAT_EQ(opaque.ior, 1.0f);  // written as 0: unused by an opaque material
  EXPECT_FALSE(opaque.fresnel);
  expectVec3Eq(opaque.ambient, Color(0.0f));
  const MaterialDesc& glass = scene.materials[1];
  EXPECT_EQ(glass.name, "f2");
  expectVec3Eq(glass.transmittance, Color(0.9f));
  EXPECT_FLOAT_EQ(glass.ior, 1.5f);

  ASSERT_EQ(scene.spheres.size(), 2u);
  expectVec3Eq(scene.spheres[0].center, Vec3(1, 2, 3));
  EXPECT_FLOAT_EQ(scene.spheres[0].radius, 0.5f);
  EXPECT_EQ(scene.spheres[0].material, 0u);
  EXPECT_EQ(scene.spheres[0].loc.line, 13);
  // Negative radius: inside-only in NFF; Prism's spheres are two-sided.
  EXPECT_FLOAT_EQ(scene.spheres[1].radius, 2.0f);
  EXPECT_EQ(scene.spheres[1].material, 1u);

  ASSERT_EQ(scene.cones.size(), 1u);
  expectVec3Eq(scene.cones[0].base, Vec3(0, 0, 0));
  EXPECT_FLOAT_EQ(scene.cones[0].baseRadius, 1.0f);
  expectVec3Eq(scene.cones[0].apex, Vec3(0, 0, 2));
  EXPECT_FLOAT_EQ(scene.cones[0].apexRadius, 0.5f);
  EXPECT_EQ(scene.cones[0].material, 0u);

  // The triangle and the quad share a flat mesh; the patch starts a smooth one.
  ASSERT_EQ(scene.meshes.size(), 2u);
  const MeshDesc& flat = scene.meshes[0];
  EXPECT_EQ(flat.source, "polygons");
  EXPECT_EQ(flat.material, 1u);
  EXPECT_EQ(flat.loc.line, 18);
  EXPECT_EQ(flat.triangleCount(), 3u);
  EXPECT_TRUE(flat.normals.empty());
  float area = 0.0f;
  for (size_t t = 0; t < flat.triangleCount(); ++t) area += triangleArea(flat, t);
  EXPECT_FLOAT_EQ(area, 1.5f);
  const MeshDesc& smooth = scene.meshes[1];
  EXPECT_EQ(smooth.triangleCount(), 1u);
  ASSERT_EQ(smooth.normals.size(), smooth.positions.size());
  expectVec3Eq(smooth.normals[0], Vec3(0, 0, 1));  // normalised from (0, 0, 2)
  EXPECT_EQ(scene.triangleCount(), 4u);
}

TEST(NffParser, PolygonTrianglesKeepTheVertexOrder) {
  // Spec: vertices run counter-clockwise seen from the visible side; here that side faces +z.
  const SceneDescription scene =
      parseNff("f 1 1 1 1 0 1 0 1\np 5\n0 0 0\n2 0 0\n2 2 0\n1 1 0\n0 2 0\n", "arrow.nff");
  ASSERT_EQ(scene.meshes.size(), 1u);
  const MeshDesc& mesh = scene.meshes[0];
  ASSERT_EQ(mesh.triangleCount(), 3u);
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    const Vec3& a = mesh.positions[mesh.indices[3 * t]];
    const Vec3& b = mesh.positions[mesh.indices[3 * t + 1]];
    const Vec3& c = mesh.positions[mesh.indices[3 * t + 2]];
    EXPECT_GT(glm::cross(b - a, c - a).z, 0.0f) << "triangle " << t;
  }
}

TEST(NffParser, NewMaterialStartsNewMesh) {
  const SceneDescription scene = parseNff(
      "f 1 1 1 1 0 1 0 1\np 3 0 0 0 1 0 0 0 1 0\np 3 0 0 1 1 0 1 0 1 1\n"
      "f 1 0 0 1 0 1 0 1\np 3 0 0 2 1 0 2 0 1 2\n",
      "two.nff");
  ASSERT_EQ(scene.meshes.size(), 2u);
  EXPECT_EQ(scene.meshes[0].triangleCount(), 2u);
  EXPECT_EQ(scene.meshes[0].material, 0u);
  EXPECT_EQ(scene.meshes[1].triangleCount(), 1u);
  EXPECT_EQ(scene.meshes[1].material, 1u);
}

TEST(NffParser, WithoutViewBlockKeepsDefaults) {
  const SceneDescription scene = parseNff("f 1 1 1 1 0 1 0 1\ns 0 0 0 1\n", "noview.nff");
  const CameraDesc defaults;
  expectVec3Eq(scene.camera.position, defaults.position);
  EXPECT_FLOAT_EQ(scene.camera.fovDegrees, defaults.fovDegrees);
  EXPECT_EQ(scene.render.width, 512);  // SPD's size
  EXPECT_EQ(scene.render.height, 512);
  EXPECT_TRUE(scene.lights.empty());
}

TEST(NffParser, EmptyTextGivesEmptyScene) {
  const SceneDescription scene = parseNff("# nothing but a comment", "empty.nff");
  EXPECT_TRUE(scene.spheres.empty());
  EXPECT_TRUE(scene.meshes.empty());
  EXPECT_TRUE(scene.materials.empty());
}

TEST(NffParser, ErrorsNameLineAndColumnOfTheToken) {
  try {
    parseNff("f 1 1 1 1 0 1 0 1\nc\n0 0 0 1\n0 0 x 1\n", "cone.nff");
    FAIL() << "expected a SceneError";
  } catch (const SceneError& error) {
    EXPECT_EQ(error.loc().file, "cone.nff");
    EXPECT_EQ(error.loc().line, 4);
    EXPECT_EQ(error.loc().column, 5);
    EXPECT_STREQ(error.what(),
                 "cone.nff:4:5: expected a number but found 'x' while reading a cone ('c')");
  }
}

TEST(NffParser, WindowsLineEndingsCountAsOneLine) {
  try {
    parseNff("f 1 1 1 1 0 1 0 1\r\ns 0 0 0 1\r\n\r\n  xyz\r\n", "crlf.nff");
    FAIL() << "expected a SceneError";
  } catch (const SceneError& error) {
    EXPECT_EQ(error.loc().line, 4);
    EXPECT_EQ(error.loc().column, 3);
    EXPECT_EQ(error.message(), "unknown NFF command 'xyz'");
  }
}

TEST(NffParser, LongBinaryWordGivesShortMessage) {
  std::string garbage(100000, '\x01');
  garbage[0] = '\xff';
  try {
    parseNff(garbage, "garbage.nff");
    FAIL() << "expected a SceneError";
  } catch (const SceneError& error) {
    EXPECT_LT(std::string(error.what()).size(), 200u);
    EXPECT_NE(std::string(error.what()).find("'\\xff\\x01"), std::string::npos) << error.what();
  }
}

// ---- the SPD scenes ----

struct SpdCounts {
  const char* file;
  size_t spheres;
  size_t cones;
  size_t triangles;  // sum of (n - 2) over the file's n-gons
  size_t materials;
  size_t lights;
  size_t smoothMeshVertices;  // 3 per 'pp' triangle
};

// Statement counts from grep over the files (see tests/data/nff/README.md).
const SpdCounts kSpdCounts[] = {
    {"balls-s2.nff", 91, 0, 2, 2, 3, 0},
    {"gears-s2.nff", 0, 0, 1153 * 2 + 16 * 142, 9, 5, 0},
    {"jacks-s1.nff", 6, 3, 0, 1, 1, 0},
    {"mount-s4.nff", 4, 0, 512, 2, 1, 0},
    {"rings-s3.nff", 420, 420, 2, 85, 3, 0},
    {"sample-s1.nff", 0, 1, 16 + 864, 5, 1, 3 * 864},
    {"teapot-s3.nff", 0, 0, 9 * 2 + 552, 3, 2, 3 * 552},
    {"tetra-s4.nff", 0, 0, 256, 1, 1, 0},
    {"tree-s7.nff", 255, 255, 2, 2, 7, 0},
};

class NffSpdScene : public testing::TestWithParam<SpdCounts> {};

TEST_P(NffSpdScene, ParsesWithExpectedCounts) {
  const SpdCounts& expected = GetParam();
  const std::string path = nffPath(expected.file);
  const SceneDescription scene = parseNff(readFile(path), path);
  EXPECT_EQ(scene.spheres.size(), expected.spheres);
  EXPECT_EQ(scene.cones.size(), expected.cones);
  EXPECT_EQ(scene.triangleCount(), expected.triangles);
  EXPECT_EQ(scene.materials.size(), expected.materials);
  ASSERT_EQ(scene.lights.size(), expected.lights);
  const float n = static_cast<float>(expected.lights);
  EXPECT_FLOAT_EQ(scene.lights[0].intensity.x, kPi * std::sqrt(n) / (2.0f * n));
  EXPECT_EQ(scene.render.width, expected.file == std::string("jacks-s1.nff") ? 256 : 512);
  size_t smoothVertices = 0;
  for (const MeshDesc& mesh : scene.meshes) {
    EXPECT_GT(mesh.triangleCount(), 0u);
    if (!mesh.normals.empty()) {
      ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
      smoothVertices += mesh.positions.size();
    }
    for (uint32_t index : mesh.indices) ASSERT_LT(index, mesh.positions.size());
    for (const Vec3& normal : mesh.normals) EXPECT_NEAR(glm::length(normal), 1.0f, 1e-5f);
  }
  EXPECT_EQ(smoothVertices, expected.smoothMeshVertices);
}

INSTANTIATE_TEST_SUITE_P(Nff, NffSpdScene, testing::ValuesIn(kSpdCounts),
                         [](const testing::TestParamInfo<SpdCounts>& info) {
                           std::string name = info.param.file;
                           name = name.substr(0, name.find('.'));
                           for (char& c : name) {
                             if (c == '-') c = '_';
                           }
                           return name;
                         });

// The gears' outlines are concave 144-gons: the triangles must cover exactly the polygons' area.
// The area per polygon is read independently here (half the Newell normal's length, exact for
// concave planar polygons).
TEST(NffParser, GearsTrianglesCoverThePolygonArea) {
  const std::string path = nffPath("gears-s2.nff");
  const std::string text = readFile(path);
  std::istringstream in(text);
  std::string word;
  double polygonArea = 0.0;
  while (in >> word) {
    if (word != "p") continue;
    int n = 0;
    in >> n;
    std::vector<Vec3> polygon(n);
    for (Vec3& v : polygon) in >> v.x >> v.y >> v.z;
    polygonArea += 0.5 * glm::length(newellNormal(polygon));
  }
  const SceneDescription scene = parseNff(text, path);
  double triangleAreaSum = 0.0;
  for (const MeshDesc& mesh : scene.meshes) {
    for (size_t t = 0; t < mesh.triangleCount(); ++t) triangleAreaSum += triangleArea(mesh, t);
  }
  EXPECT_GT(polygonArea, 1.0);
  EXPECT_NEAR(triangleAreaSum, polygonArea, 1e-5 * polygonArea);
}

// ---- bad input ----

struct BadNff {
  const char* file;
  int line;
  int column;
  const char* message;  // a fragment of the message
};

const BadNff kBadNff[] = {
    {"unknown_command.nff", 2, 1, "unknown NFF command 'xyz'"},
    {"letter_for_number.nff", 2, 7, "expected a number but found 'abc' while reading a sphere"},
    {"truncated_polygon.nff", 2, 1, "unexpected end of file while reading a polygon"},
    {"truncated_cone.nff", 2, 1, "unexpected end of file while reading a cone"},
    {"zero_radius.nff", 2, 11, "sphere radius must not be zero"},
    {"ior_below_one.nff", 1, 24, "index of refraction must be at least 1 for a transparent"},
    {"polygon_two_vertices.nff", 2, 3, "a polygon needs at least 3 vertices (got 2)"},
    {"nan_coordinate.nff", 2, 5, "non-finite number 'nan'"},
    {"binary_garbage.nff", 1, 1, "unknown NFF command '\\x89PNG'"},
    {"primitive_before_material.nff", 2, 1, "no material defined yet (an 'f' line must come"},
    {"cone_mixed_sign_radii.nff", 2, 18, "cone radii must both be negative"},
    {"resolution_zero.nff", 7, 16, "resolution must be positive"},
    {"polygon_extra_vertex.nff", 6, 1, "unexpected number '0'"},
    {"view_keyword_outside_view.nff", 2, 1, "'angle' belongs in a viewpoint block"},
    {"patch_zero_normal.nff", 4, 7, "vertex normal has zero length"},
    {"number_out_of_range.nff", 2, 9, "number '1e999' is out of range"},
    {"cone_apex_at_base.nff", 2, 11, "cone apex is at the same point as its base"},
    {"camera_at_equals_from.nff", 3, 1, "the 'at' point is the same as the 'from' point"},
    {"negative_background.nff", 1, 7, "colour components must not be negative"},
    {"truncated_light.nff", 1, 1, "unexpected end of file while reading a light"},
    {"transmittance_above_one.nff", 1, 16, "transmittance T must be between 0 and 1"},
    {"polygon_count_not_integer.nff", 2, 3, "expected a whole number but found '3.5'"},
};

class NffBadInput : public testing::TestWithParam<BadNff> {};

TEST_P(NffBadInput, FailsWithLocatedMessage) {
  const BadNff& bad = GetParam();
  const std::string path = PRISM_TEST_DATA_DIR "/bad/" + std::string(bad.file);
  try {
    parseNff(readFile(path), path);
    FAIL() << bad.file << " parsed without error";
  } catch (const SceneError& error) {
    EXPECT_EQ(error.loc().file, path);
    EXPECT_EQ(error.loc().line, bad.line) << error.what();
    EXPECT_EQ(error.loc().column, bad.column) << error.what();
    EXPECT_NE(error.message().find(bad.message), std::string::npos) << error.what();
    const std::string prefix =
        path + ":" + std::to_string(bad.line) + ":" + std::to_string(bad.column) + ": ";
    EXPECT_EQ(std::string(error.what()).rfind(prefix, 0), 0u) << error.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Nff, NffBadInput, testing::ValuesIn(kBadNff),
                         [](const testing::TestParamInfo<BadNff>& info) {
                           std::string name = info.param.file;
                           return name.substr(0, name.find('.'));
                         });

}  // namespace
}  // namespace prism
