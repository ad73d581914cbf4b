#include "parse/ObjLoader.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string_view>

#include "fuzz/MemoryFiles.h"
#include "image/PngFile.h"

namespace prism {
namespace {

namespace fs = std::filesystem;
using namespace std::string_view_literals;

const FileLoc kReferencedFrom{"scene.yaml", 7, 11};

// The one mesh of an OBJ model, for the tests of its geometry.
MeshDesc loadMesh(const std::string& path, const FileLoc& referencedFrom,
                  const MemoryLimit& limit = {}) {
  ModelDesc model = loadObjModel(path, referencedFrom, limit);
  EXPECT_EQ(model.meshes.size(), 1u);
  return std::move(model.meshes.at(0));
}
MeshDesc parseMesh(std::string_view text, const std::string& path, const FileLoc& referencedFrom,
                   const MemoryLimit& limit = {}, size_t pieceBytes = 0) {
  ModelDesc model = parseObjModel(text, path, referencedFrom, limit, pieceBytes);
  EXPECT_EQ(model.meshes.size(), 1u);
  return std::move(model.meshes.at(0));
}

std::string objPath(const std::string& name) {
  return PRISM_TEST_DATA_DIR "/obj/" + name;
}

// Writes small OBJ files for one test into a private temporary folder.
class ObjFiles : public testing::Test {
 protected:
  void SetUp() override {
    const auto* info = testing::UnitTest::GetInstance()->current_test_info();
    std::string name = info->name();
    std::replace(name.begin(), name.end(), '/', '_');  // parameterised tests: "Test/param"
    dir_ = fs::temp_directory_path() / ("prism_obj_" + std::to_string(::getpid()) + "_" + name);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, std::string_view text) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }

  fs::path dir_;
};

Vec3 geometricNormal(const MeshDesc& mesh, size_t t) {
  const Vec3& a = mesh.positions[mesh.indices[3 * t]];
  const Vec3& b = mesh.positions[mesh.indices[3 * t + 1]];
  const Vec3& c = mesh.positions[mesh.indices[3 * t + 2]];
  return glm::cross(b - a, c - a);
}

float meshArea(const MeshDesc& mesh) {
  float area = 0.0f;
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    area += 0.5f * glm::length(geometricNormal(mesh, t));
  }
  return area;
}

TEST(ObjLoader, SeparatelyIndexedNormalsBecomeVertexNormals) {
  const MeshDesc mesh = loadMesh(objPath("cube_normals.obj"), kReferencedFrom);
  EXPECT_EQ(mesh.source, objPath("cube_normals.obj"));
  EXPECT_EQ(mesh.material, 0u);
  EXPECT_EQ(mesh.triangleCount(), 12u);   // six quads, two shapes merged
  EXPECT_EQ(mesh.positions.size(), 24u);  // each corner once per face normal
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const Vec3& p = mesh.positions[i];
    EXPECT_EQ(glm::abs(p), Vec3(1.0f)) << "vertex " << i;
    // Every corner lies on the face its normal belongs to.
    EXPECT_FLOAT_EQ(glm::dot(p, mesh.normals[i]), 1.0f) << "vertex " << i;
  }
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    const Vec3 faceNormal = glm::normalize(geometricNormal(mesh, t));
    for (int k = 0; k < 3; ++k) {
      EXPECT_FLOAT_EQ(glm::dot(faceNormal, mesh.normals[mesh.indices[3 * t + k]]), 1.0f)
          << "triangle " << t;
    }
  }
  EXPECT_FLOAT_EQ(meshArea(mesh), 24.0f);
}

TEST(ObjLoader, QuadWithoutNormalsGivesTwoFlatTriangles) {
  const MeshDesc mesh = loadMesh(objPath("quad.obj"), kReferencedFrom);
  EXPECT_EQ(mesh.triangleCount(), 2u);
  EXPECT_EQ(mesh.positions.size(), 4u);
  EXPECT_TRUE(mesh.normals.empty());
  EXPECT_FLOAT_EQ(meshArea(mesh), 1.0f);
  for (size_t t = 0; t < 2; ++t) EXPECT_GT(geometricNormal(mesh, t).z, 0.0f);
  EXPECT_EQ(mesh.loc.file, kReferencedFrom.file);
  EXPECT_EQ(mesh.loc.line, kReferencedFrom.line);
}

TEST_F(ObjFiles, OneFaceWithoutNormalsMakesTheMeshFlat) {
  const std::string path = write("mixed.obj",
                                 "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\n"
                                 "f 1//1 2//1 3//1\nf 2 4 3\n");
  const MeshDesc mesh = loadMesh(path, kReferencedFrom);
  EXPECT_EQ(mesh.triangleCount(), 2u);
  EXPECT_TRUE(mesh.normals.empty());
  EXPECT_EQ(mesh.positions.size(), 4u);  // shared corners are shared again once normals go
}

TEST_F(ObjFiles, ZeroNormalMakesTheMeshFlat) {
  const std::string path =
      write("zero_normal.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 0\nf 1//1 2//1 3//1\n");
  EXPECT_TRUE(loadMesh(path, kReferencedFrom).normals.empty());
}

TEST(ObjLoader, NormalsTooSmallOrTooLargeToNormaliseMakeTheMeshFlat) {
  for (const char* normal : {"1e-30 1e-30 1e-30", "1e30 1e30 1e30", "1e-45 0 0"}) {
    std::string text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn ";
    text += normal;
    text += "\nf 1//1 2//1 3//1\n";
    EXPECT_TRUE(parseMesh(text, "mem.obj", {}).normals.empty()) << normal;
  }
  const MeshDesc tiny =
      parseMesh("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1e-20\nf 1//1 2//1 3//1\n", "m.obj", {});
  ASSERT_EQ(tiny.normals.size(), 3u);  // small, but its length is a normal float
  EXPECT_NEAR(tiny.normals[0].z, 1.0f, 1e-5f);
}

TEST_F(ObjFiles, ConcaveFaceIsEarClipped) {
  // An L-shaped hexagon with texture coordinates and relative (negative) indices.
  const std::string path = write("l_shape.obj",
                                 "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\n"
                                 "vt 0 0\nf -6/1 -5/1 -4/1 -3/1 -2/1 -1/1\n");
  const MeshDesc mesh = loadMesh(path, kReferencedFrom);
  EXPECT_EQ(mesh.triangleCount(), 4u);
  EXPECT_FLOAT_EQ(meshArea(mesh), 3.0f);
  for (size_t t = 0; t < 4; ++t) EXPECT_GT(geometricNormal(mesh, t).z, 0.0f);
}

TEST(ObjLoader, TextInMemoryLoadsLikeTheFileAndErrorsNameThePath) {
  const MeshDesc mesh =
      parseMesh("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n", "mem.obj", kReferencedFrom);
  EXPECT_EQ(mesh.source, "mem.obj");
  EXPECT_EQ(mesh.triangleCount(), 2u);
  EXPECT_FLOAT_EQ(meshArea(mesh), 1.0f);
  try {
    parseMesh("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "mem.obj", kReferencedFrom);
    FAIL() << "expected a SceneError";
  } catch (const SceneError& error) {
    EXPECT_EQ(error.loc().file, "mem.obj");
    EXPECT_EQ(error.loc().line, 4);
    EXPECT_EQ(error.message(), "face refers to vertex 9 but the file has 3");
  }
}

TEST(ObjLoader, MissingFileIsReportedWhereTheSceneNamesIt) {
  try {
    loadMesh("no/such/mesh.obj", kReferencedFrom);
    FAIL() << "expected a SceneError";
  } catch (const SceneError& error) {
    EXPECT_EQ(error.loc().file, "scene.yaml");
    EXPECT_EQ(error.loc().line, 7);
    EXPECT_EQ(error.loc().column, 11);
    EXPECT_EQ(error.message(),
              "cannot open mesh file 'no/such/mesh.obj': No such file or directory");
  }
}

TEST_F(ObjFiles, DirectoryIsNotAMeshFile) {
  try {
    loadMesh(dir_.string(), kReferencedFrom);
    FAIL() << "expected a SceneError";
  } catch (const SceneError& error) {
    EXPECT_EQ(error.loc().file, "scene.yaml");
    EXPECT_NE(error.message().find("Is a directory"), std::string::npos) << error.what();
  }
}

struct BadObj {
  const char* name;
  std::string_view text;
  int line;  // 0: the error names the file only
  int column;
  const char* message;
};

const BadObj kBadObj[] = {
    {"empty", "# nothing here\n", 0, 0, "mesh file has no triangles"},
    {"no_faces", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", 0, 0, "mesh file has no triangles"},
    {"binary",
     "\x7f"
     "ELF\x02\x01\x01\x00\x00\x00\xff\xfe\n\x00\x13\x37"sv,
     0, 0, "mesh file has no triangles"},
    {"vertex_index_out_of_range", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n", 5, 7,
     "face refers to vertex 9 but the file has 3"},
    {"relative_index_out_of_range", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", 4, 9,
     "face refers to vertex -4 but only 3 come before it"},
    {"relative_index_counts_only_what_comes_before", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n", 3,
     9, "face refers to vertex -3 but only 2 come before it"},
    {"big_face_index_out_of_range",
     "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 2 0\nf 1 2 3 4 5 999999\n", 6, 13,
     "face refers to vertex 999999"},
    {"normal_index_out_of_range", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n", 5, 13,
     "face refers to normal 2 but the file has 1"},
    {"zero_index", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", 4, 3,
     "face refers to vertex 0 (OBJ counts from 1)"},
    {"zero_texture_index", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/0 3/1\n", 5, 7,
     "face refers to texture coordinate 0 (OBJ counts from 1)"},
    {"letter_index", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2x 3\n", 4, 5,
     "expected a face corner (v, v/vt, v//vn or v/vt/vn) but found '2x'"},
    {"corner_of_four_fields", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3/1/1/1\n", 4, 7,
     "expected a face corner"},
    {"letter_normal", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 y 1\nf 1//1 2//1 3//1\n", 4, 6,
     "expected a number but found 'y'"},
    {"short_normal", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 1\nf 1//1 2//1 3//1\n", 4, 1,
     "normal needs 3 coordinates"},
    {"two_vertex_face", "v 0 0 0\nv 1 0 0\nf 1 2\n", 3, 1, "face needs at least 3 vertices"},
    {"nan_vertex", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n", 2, 5, "non-finite coordinate 'nan'"},
    {"huge_vertex", "v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n", 2, 3, "non-finite coordinate"},
    {"letter_vertex", "v 0 0 0\nv 1 x 0\nv 0 1 0\nf 1 2 3\n", 2, 5,
     "expected a number but found 'x'"},
    {"crlf_letter_vertex", "v 0 0 0\r\nv 1 0 0\r\nv 0 x 1\r\nf 1 2 3\r\n", 3, 5,
     "expected a number but found 'x'"},
    {"cr_only_index_out_of_range", "v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 4\r", 4, 7,
     "face refers to vertex 4"},
    {"binary_in_vertex", "v 0 0 0\nv 1 \xff\xfe 0\n", 2, 5, "found '\\xff\\xfe'"},
    {"short_vertex", "v 0 0\nf 1 1 1\n", 1, 1, "vertex needs 3 coordinates"},
};

class ObjBadInput : public ObjFiles, public testing::WithParamInterface<BadObj> {};

TEST_P(ObjBadInput, FailsInsideTheObjFile) {
  const BadObj& bad = GetParam();
  const std::string path = write(std::string(bad.name) + ".obj", bad.text);
  try {
    loadMesh(path, kReferencedFrom);
    FAIL() << bad.name << " loaded without error";
  } catch (const SceneError& error) {
    EXPECT_EQ(error.loc().file, path);
    EXPECT_EQ(error.loc().line, bad.line) << error.what();
    EXPECT_EQ(error.loc().column, bad.column) << error.what();
    EXPECT_NE(error.message().find(bad.message), std::string::npos) << error.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Obj, ObjBadInput, testing::ValuesIn(kBadObj),
                         [](const testing::TestParamInfo<BadObj>& info) {
                           return std::string(info.param.name);
                         });

}  // namespace
}  // namespace prism

namespace prism {
namespace {

// Four positions, one quad (4 corners, 2 triangles), 42 bytes of text. Reading: 42 + 4 x 32 +
// 4 x 4 + 1 + 2 x 12 = 211; building: 2 x 212 + 4 x 64 = 680; 891 bytes in all.
constexpr std::string_view kQuad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";

TEST_F(ObjFiles, AMeshPastTheMemoryLimitIsRefusedBeforeItIsRead) {
  const std::string path = write("quad.obj", kQuad);
  EXPECT_EQ(loadMesh(path, kReferencedFrom, {891, "test"}).triangleCount(), 2u);
  try {
    loadMesh(path, kReferencedFrom, {890, "test"});
    FAIL() << "expected a refusal";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              "scene.yaml:7:11: mesh file '" + path +
                  "' (2 triangles, 4 vertices) read and built needs 891 B (891 bytes); the "
                  "memory limit is 890 B (890 bytes, test): simplify the mesh or raise "
                  "--memory-limit");
  }
  try {  // smaller than the file itself: refused before a byte is read
    loadMesh(path, kReferencedFrom, {41, "test"});
    FAIL() << "expected a refusal";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              "scene.yaml:7:11: reading mesh file '" + path +
                  "' needs 42 B (42 bytes); the memory limit is 41 B (41 bytes, test): simplify "
                  "the mesh or raise --memory-limit");
  }
}

}  // namespace
}  // namespace prism

namespace prism {
namespace {

bool sameMesh(const MeshDesc& a, const MeshDesc& b) {
  return a.positions == b.positions && a.normals == b.normals && a.indices == b.indices &&
         a.uvs == b.uvs && a.faceMaterials == b.faceMaterials && a.material == b.material;
}

// Every line ending, relative indices, normals, a polygon, comments and skipped statements.
constexpr std::string_view kEverything =
    "# header\r\nmtllib none.mtl\nv 0 0 0\r\nv 2 0 0\rv 2 1 0\nv 1 1 0\n\nv 1 2 0\n"
    "v 0 2 0 # six\nvn 0 0 3\r\nvt 0 0\ng part\nusemtl x\ns 1\n"
    "f -6/1/1 -5/1/1 -4/1/1 -3/1/1 -2/1/1 -1/1/1\r\n"
    "vn 0 0 2\nf 1//-2 2//-2 6//1 # a triangle\n  \t f 4//1 5//1 6//1";

TEST(ObjLoader, TheMeshIsTheSameHoweverTheTextIsCutForTheThreads) {
  const MeshDesc whole = parseMesh(kEverything, "mem.obj", kReferencedFrom);
  EXPECT_EQ(whole.triangleCount(), 4u + 1u + 1u);
  // One normal per position, but the hexagon's corners have a texture coordinate and the last
  // two faces' corners none: the five corners of those faces are new vertices.
  EXPECT_EQ(whole.positions.size(), 6u + 5u);
  ASSERT_EQ(whole.normals.size(), 11u);
  ASSERT_EQ(whole.uvs.size(), 11u);
  for (const Vec3& n : whole.normals) EXPECT_EQ(n, Vec3(0, 0, 1));  // normalised
  EXPECT_FLOAT_EQ(meshArea(whole), 3.0f + 2.0f + 0.5f);
  for (size_t piece = 1; piece <= kEverything.size(); ++piece) {
    const MeshDesc cut = parseMesh(kEverything, "mem.obj", kReferencedFrom, {}, piece);
    EXPECT_TRUE(sameMesh(cut, whole)) << "pieces of " << piece << " bytes";
  }
}

TEST(ObjLoader, TheFirstErrorIsFoundHoweverTheTextIsCut) {
  // Line 6 has the first error; line 8 has another.
  const std::string text = "v 0 0 0\r\nv 1 0 0\rv 0 1 0\n# ok\nf 1 2 3\nf 1 2 -9\nv x 0 0\n";
  for (size_t piece = 1; piece <= text.size(); ++piece) {
    try {
      parseMesh(text, "mem.obj", kReferencedFrom, {}, piece);
      ADD_FAILURE() << "no error with pieces of " << piece << " bytes";
    } catch (const SceneError& error) {
      EXPECT_EQ(error.loc().line, 6) << "pieces of " << piece << " bytes";
      EXPECT_EQ(error.loc().column, 7) << "pieces of " << piece << " bytes";
      EXPECT_EQ(error.message(), "face refers to vertex -9 but only 3 come before it");
    }
  }
}

TEST(ObjLoader, FacesMayNameVerticesThatComeLater) {
  const MeshDesc mesh = parseMesh("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", "mem.obj", {});
  EXPECT_EQ(mesh.triangleCount(), 1u);
  EXPECT_EQ(mesh.positions[1], Vec3(1, 0, 0));
}

TEST(ObjLoader, UnusedVerticesAreDroppedAndTheRestNumberedInTheOrderFacesUseThem) {
  const MeshDesc mesh = parseMesh("v 9 9 9\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 4 2 3\n", "mem.obj", {});
  EXPECT_EQ(mesh.positions, (std::vector<Vec3>{{0, 1, 0}, {0, 0, 0}, {1, 0, 0}}));
  EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2}));
}

TEST(ObjLoader, APositionWithTwoNormalsBecomesTwoVertices) {
  const MeshDesc mesh = parseMesh(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\nvn 0 1 1\n"
      "f 1//1 2//1 3//1\nf 2//2 4//2 3//1\n",
      "mem.obj", {});
  EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 2}));
  ASSERT_EQ(mesh.positions.size(), 5u);
  EXPECT_EQ(mesh.positions[3], Vec3(1, 0, 0));  // position 2 again, with the second normal
  EXPECT_FLOAT_EQ(mesh.normals[3].y, std::sqrt(0.5f));
}

TEST(ObjLoader, AFaceOf255CornersIsReadAndOneOf256Refused) {
  for (const int corners : {255, 256}) {
    std::string text;
    for (int i = 0; i < corners; ++i) {
      const double a = 2 * 3.14159265358979 * i / corners;
      text += "v " + std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
    }
    text += "f";
    for (int i = 1; i <= corners; ++i) {
      text += ' ';
      text += std::to_string(i);
    }
    if (corners == 255) {
      EXPECT_EQ(parseMesh(text, "mem.obj", {}).triangleCount(), 253u);
    } else {
      try {
        parseMesh(text, "mem.obj", {});
        ADD_FAILURE() << "a face of 256 corners was read";
      } catch (const SceneError& error) {
        EXPECT_EQ(error.loc().line, 257);
        EXPECT_EQ(error.message(), "face has more than 255 vertices");
      }
    }
  }
}

}  // namespace
}  // namespace prism

namespace prism {
namespace {

// An OBJ's material libraries and textures, in memory (fuzz/MemoryFiles.h).
TextureDesc twoByTwo() {
  TextureDesc texture;
  texture.srgb.width = 2;
  texture.srgb.height = 2;
  texture.srgb.rgb.assign(12, 128);
  return texture;
}

MemoryFiles libraryFiles() {
  MemoryFiles files;
  files.add("lib.mtl",
            "newmtl red\nKd 1 0 0\n"
            "newmtl green\nKd 0 1 0\nmap_Kd unused.png\n"
            "newmtl blue\nKd 0 0 1\nmap_Kd -s 2 4 -o 0.5 0.25 tex.png\n"
            "newmtl white\nmap_Kd ./tex.png\n");
  files.addTexture("tex.png", twoByTwo());
  files.addTexture("unused.png", twoByTwo());
  return files;
}

// A square in four triangles: one before any usemtl, then red, blue (its texture coordinates by
// negative indices) and red again.
constexpr std::string_view kSquare =
    "mtllib lib.mtl\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "f 1/1 2/2 3/3\n"
    "usemtl red\nf 1/1 3/3 4/4\n"
    "usemtl blue\nf 1/-4 2/-3 4/-1\n"
    "usemtl red\nf 2/2 3/3 4/4\n";

std::vector<std::string> materialNames(const ModelDesc& model) {
  std::vector<std::string> names;
  for (const MaterialDesc& m : model.materials) names.push_back(m.name);
  return names;
}

TEST(ObjModel, UsemtlGivesEachFaceItsMaterialAndFacesBeforeAnyGetTheDefault) {
  const MemoryFiles files = libraryFiles();
  const ModelDesc model = parseObjModel(kSquare, "mem.obj", kReferencedFrom, {}, 0, files);
  EXPECT_TRUE(model.warnings.empty()) << model.warnings.front();
  // The materials faces use, in the order the library defines them, then the default.
  EXPECT_EQ(materialNames(model), (std::vector<std::string>{"red", "blue", "default (mem.obj)"}));
  EXPECT_EQ(model.materials[0].diffuse, Color(1, 0, 0));
  EXPECT_EQ(model.materials[2].diffuse, Color(0.8f));
  ASSERT_EQ(model.meshes.size(), 1u);
  EXPECT_EQ(model.meshes[0].faceMaterials, (std::vector<MaterialId>{2, 0, 1, 0}));
  // Only blue's texture is read: green is not used.
  ASSERT_EQ(model.textures.size(), 1u);
  EXPECT_EQ(model.textures[0].path, "tex.png");
  EXPECT_EQ(files.reads("unused.png"), 0);
  ASSERT_TRUE(model.materials[1].diffuseMap);
  EXPECT_EQ(model.materials[1].diffuseMap->texture, 0u);
  EXPECT_EQ(model.materials[1].diffuseMap->scale, Vec2(2.0f, 4.0f));
  EXPECT_EQ(model.materials[1].diffuseMap->offset, Vec2(0.5f, 0.25f));
}

TEST(ObjModel, TextureCoordinatesFollowTheCornersNegativeIndicesIncluded) {
  const MemoryFiles files = libraryFiles();
  const MeshDesc mesh =
      parseObjModel(kSquare, "mem.obj", kReferencedFrom, {}, 0, files).meshes.at(0);
  ASSERT_EQ(mesh.uvs.size(), mesh.positions.size());
  const Vec2 uvOfPosition[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (size_t k = 0; k < mesh.indices.size(); ++k) {
    const Vec3& p = mesh.positions[mesh.indices[k]];
    const int position = p == Vec3(0, 0, 0)   ? 0
                         : p == Vec3(1, 0, 0) ? 1
                         : p == Vec3(1, 1, 0) ? 2
                                              : 3;
    EXPECT_EQ(mesh.uvs[mesh.indices[k]], uvOfPosition[position]) << "corner " << k;
  }
  EXPECT_EQ(mesh.positions.size(), 4u);  // each position has one texture coordinate
}

TEST(ObjModel, APositionWithTwoTextureCoordinatesBecomesTwoVertices) {
  const ModelDesc model = parseObjModel(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0.25 0.5\nvt 0.75\n"
      "f 1/1 2/1 3/1\nf 2/2 4/2 3/1\n",
      "mem.obj", {});
  const MeshDesc& mesh = model.meshes.at(0);
  EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 2}));
  EXPECT_EQ(mesh.positions.size(), 5u);
  EXPECT_EQ(mesh.positions[3], Vec3(1, 0, 0));
  EXPECT_EQ(mesh.uvs, (std::vector<Vec2>{{0.25f, 0.5f},
                                         {0.25f, 0.5f},
                                         {0.25f, 0.5f},
                                         {0.75f, 0.0f},
                                         {0.75f, 0.0f}}));  // v: 0 when absent
  EXPECT_TRUE(model.materials.empty());
}

TEST(ObjModel, AFileWithoutMaterialsOrTextureCoordinatesIsItsGeometryAlone) {
  const ModelDesc model = parseObjModel(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 1//1 3//1 4//1\n",
      "mem.obj", {});
  EXPECT_TRUE(model.materials.empty());
  EXPECT_TRUE(model.textures.empty());
  EXPECT_TRUE(model.warnings.empty());
  const MeshDesc& mesh = model.meshes.at(0);
  EXPECT_EQ(mesh.material, 0u);
  EXPECT_TRUE(mesh.faceMaterials.empty());
  EXPECT_TRUE(mesh.uvs.empty());
  EXPECT_TRUE(mesh.colors.empty());
  EXPECT_EQ(mesh.positions, (std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}));
  EXPECT_EQ(mesh.normals.size(), 4u);
  EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
}

TEST(ObjModel, OneMaterialForEveryFaceIsTheMeshsMaterial) {
  const MemoryFiles files = libraryFiles();
  const ModelDesc model =
      parseObjModel("mtllib lib.mtl\nusemtl blue\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 3 2 1\n",
                    "mem.obj", {}, {}, 0, files);
  EXPECT_EQ(materialNames(model), std::vector<std::string>{"blue"});
  EXPECT_EQ(model.meshes.at(0).material, 0u);
  EXPECT_TRUE(model.meshes.at(0).faceMaterials.empty());
  EXPECT_TRUE(model.meshes.at(0).uvs.empty());
}

TEST(ObjModel, TheModelIsTheSameHoweverTheTextIsCutForTheThreads) {
  const MemoryFiles files = libraryFiles();
  // Materials switch between and within what the pieces hold; a usemtl names nothing defined;
  // a polygon; texture coordinates on some faces only.
  const std::string text =
      "f 1/1 2/2 3/3\nmtllib lib.mtl\r\nv 0 0 0\nv 1 0 0\rv 1 1 0\nv 0 1 0\nv -1 0.5 0\n"
      "vt 0 0\nvt 1 0\nvt 1 1\nf 1/1 2/2 3/3\nusemtl red\nf 1/1 3/3 4/1\n# comment\n"
      "usemtl blue\n\nf 1/-3 2/-2 4/-1\nf 4 3 5\nusemtl nothing\nf 1 2 3 4 5\n"
      "usemtl white # a comment\nf 2/2 3/3 4/1\nusemtl red\nusemtl blue\n  f 5 4 1";
  const ModelDesc whole = parseObjModel(text, "mem.obj", kReferencedFrom, {}, 0, files);
  EXPECT_EQ(materialNames(whole),
            (std::vector<std::string>{"red", "blue", "white", "default (mem.obj)"}));
  EXPECT_EQ(whole.meshes.at(0).faceMaterials,
            (std::vector<MaterialId>{3, 3, 0, 1, 1, 3, 3, 3, 2, 1}));
  EXPECT_EQ(whole.textures.size(), 1u);  // tex.png and ./tex.png are one file
  ASSERT_EQ(whole.warnings.size(), 2u);
  EXPECT_EQ(whole.warnings[0],
            "mem.obj:19: usemtl 'nothing' names no material the material libraries define; "
            "their faces get the default material");
  EXPECT_EQ(whole.warnings[1],
            "mem.obj:18: face corners without texture coordinates beside corners with them; "
            "they read textures at (0, 0)");
  for (size_t piece = 1; piece <= text.size(); ++piece) {
    const ModelDesc cut = parseObjModel(text, "mem.obj", kReferencedFrom, {}, piece, files);
    EXPECT_TRUE(sameMesh(cut.meshes.at(0), whole.meshes.at(0))) << "pieces of " << piece;
    EXPECT_EQ(materialNames(cut), materialNames(whole)) << "pieces of " << piece;
    EXPECT_EQ(cut.warnings, whole.warnings) << "pieces of " << piece;
    EXPECT_EQ(cut.textures.size(), whole.textures.size()) << "pieces of " << piece;
  }
}

TEST(ObjModel, AMissingLibraryIsAWarningAndItsMaterialsTheDefault) {
  const ModelDesc model = parseObjModel(
      "mtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n", "dir/m.obj", {});
  EXPECT_TRUE(model.materials.empty());  // the scene's material covers the mesh
  EXPECT_EQ(model.warnings,
            (std::vector<std::string>{
                "dir/m.obj:1: material library 'missing.mtl' not found (looked for "
                "'dir/missing.mtl'); faces that use its materials get the default material",
                "dir/m.obj:5: usemtl 'red' names no material (no material library was read); "
                "their faces get the default material"}));
}

TEST(ObjModel, UsemtlOfNamesNoLibraryDefinesIsOneWarning) {
  const MemoryFiles files = libraryFiles();
  const ModelDesc model = parseObjModel(
      "mtllib lib.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl nope\nf 1 2 3\nusemtl red\nf 1 2 3\n"
      "usemtl other\nf 3 2 1\nusemtl nope\nf 1 3 2\n",
      "m.obj", {}, {}, 0, files);
  EXPECT_EQ(materialNames(model), (std::vector<std::string>{"red", "default (m.obj)"}));
  EXPECT_EQ(model.meshes.at(0).faceMaterials, (std::vector<MaterialId>{1, 0, 1, 1}));
  EXPECT_EQ(model.warnings,
            std::vector<std::string>{
                "m.obj:5: usemtl 'nope' names no material the material libraries define, nor do "
                "1 other names; their faces get the default material"});
}

TEST(ObjModel, MtllibReadsNamesWithBlanksBackslashesAndSeveralFilesOnce) {
  MemoryFiles files;
  files.add("models/my lib.mtl", "newmtl a\n");
  files.add("models/sub/b.mtl", "newmtl b\n");
  files.add("models/c.mtl", "newmtl c\n");
  files.add("models/d.mtl", "newmtl d\nnewmtl a\nKd 1 1 1\n");
  files.add("models/e.mtl", "newmtl e\n");
  const std::string text =
      "mtllib my lib.mtl\nmtllib sub\\b.mtl c.mtl\nmtllib C:\\Users\\me\\d.mtl\n"
      "mtllib c.mtl ./e.mtl gone.mtl\n"
      "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
      "usemtl a\nf 1 2 3\nusemtl b\nf 1 2 3\nusemtl c\nf 1 2 3\nusemtl d\nf 1 2 3\n"
      "usemtl e\nf 1 2 3\n";
  const ModelDesc model = parseObjModel(text, "models/m.obj", {}, {}, 0, files);
  EXPECT_EQ(materialNames(model), (std::vector<std::string>{"a", "b", "c", "d", "e"}));
  EXPECT_EQ(model.materials[0].diffuse, Color(0.8f));  // the first 'a' wins
  EXPECT_EQ(files.reads("models/c.mtl"), 1);
  EXPECT_EQ(model.warnings,
            (std::vector<std::string>{
                "models/d.mtl:2: material 'a' is defined again; the first definition is used",
                "models/m.obj:4: material library 'gone.mtl' not found (looked for "
                "'models/gone.mtl'); faces that use its materials get the default material"}));
}

TEST(ObjModel, TexturesAreFoundBesideTheirLibraryAndReadOnce) {
  MemoryFiles files;
  files.add("models/mats/lib.mtl",
            "newmtl a\nmap_Kd ../tex/t.png\nnewmtl b\nmap_Kd ..\\tex\\t.png\n"
            "newmtl c\nmap_Kd D:\\art\\beside.png\n");
  files.addTexture("models/tex/t.png", twoByTwo());
  files.addTexture("models/mats/beside.png", twoByTwo());
  const ModelDesc model = parseObjModel(
      "mtllib mats/lib.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\nusemtl b\nf 1 2 3\n"
      "usemtl c\nf 1 2 3\n",
      "models/m.obj", {}, {}, 0, files);
  ASSERT_EQ(model.textures.size(), 2u);
  EXPECT_EQ(model.textures[0].path, "models/tex/t.png");
  EXPECT_EQ(model.textures[1].path, "models/mats/beside.png");
  EXPECT_EQ(files.reads("models/tex/t.png"), 1);
  EXPECT_EQ(model.materials[0].diffuseMap->texture, 0u);
  EXPECT_EQ(model.materials[1].diffuseMap->texture, 0u);
  EXPECT_EQ(model.materials[2].diffuseMap->texture, 1u);
  EXPECT_TRUE(model.warnings.empty());
}

TEST(ObjModel, AMissingTextureIsAWarningAndTheMaterialKeepsItsColour) {
  MemoryFiles files;
  files.add("lib.mtl", "newmtl a\nKd 0.5\nmap_Kd -s 2 2 wood grain.jpg\n");
  const ModelDesc model = parseObjModel(
      "mtllib lib.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n", "m.obj", {}, {}, 0, files);
  ASSERT_EQ(model.materials.size(), 1u);
  EXPECT_FALSE(model.materials[0].diffuseMap);
  EXPECT_EQ(model.materials[0].diffuse, Color(0.5f));
  EXPECT_TRUE(model.textures.empty());
  EXPECT_EQ(model.warnings,
            std::vector<std::string>{
                "lib.mtl:3: texture 'wood grain.jpg' not found (looked for 'wood grain.jpg'); "
                "material 'a' shows its diffuse colour without it"});
}

TEST(ObjModel, ATextureThatIsNotAnImageIsAnErrorAtItsMapStatement) {
  MemoryFiles files;
  files.add("lib.mtl", "newmtl a\nmap_Kd  bad.png\n");
  files.add("bad.png", "not an image at all");
  try {
    parseObjModel("mtllib lib.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n", "m.obj", {}, {},
                  0, files);
    FAIL() << "expected a SceneError";
  } catch (const SceneError& error) {
    EXPECT_EQ(error.loc().file, "lib.mtl");
    EXPECT_EQ(error.loc().line, 2);
    EXPECT_EQ(error.loc().column, 9);
    EXPECT_NE(error.message().find("bad.png"), std::string::npos) << error.what();
  }
}

TEST(ObjModel, AMalformedLibraryIsAnErrorInTheLibrary) {
  MemoryFiles files;
  files.add("lib.mtl", "newmtl a\nKd 1 0 0\nNs fast\n");
  try {
    parseObjModel("mtllib lib.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "m.obj", {}, {}, 0,
                  files);
    FAIL() << "expected a SceneError";
  } catch (const SceneError& error) {
    EXPECT_EQ(std::string(error.what()), "lib.mtl:3:4: expected a number but found 'fast'");
  }
}

TEST_F(ObjFiles, ALibraryAndItsPngOnDiskMakeATexturedModel) {
  const uint8_t rgb[12] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};
  writePng((dir_ / "checker.png").string(), 2, 2, rgb, ImageMetadata{});
  write("box materials.mtl", "newmtl checker\nKd 1 1 1\nmap_Kd checker.png\nBump n.png\n");
  const std::string path =
      write("box.obj",
            "mtllib box materials.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
            "usemtl checker\nf 1/1 2/2 3/3\n");
  const ModelDesc model = loadObjModel(path, kReferencedFrom);
  ASSERT_EQ(model.textures.size(), 1u);
  EXPECT_TRUE(model.textures[0].keptAsBytes());
  EXPECT_EQ(model.textures[0].width(), 2);
  EXPECT_EQ(model.textures[0].srgb.rgb[0], 255);
  ASSERT_EQ(model.materials.size(), 1u);
  EXPECT_EQ(model.materials[0].diffuseMap->texture, 0u);
  EXPECT_EQ(model.meshes.at(0).uvs.size(), 3u);
  EXPECT_EQ(model.warnings,
            std::vector<std::string>{(dir_ / "box materials.mtl").string() +
                                     ":4: 'Bump' (bump map) is not modelled by Prism; it is "
                                     "skipped"});
}

// Four positions with texture coordinates, one quad: reading 4 x (12 + 8 + 12 + 8 + 8) for the
// positions, 4 x 8 for the coordinates, 4 x 8 for the corners, 1 for the face, 2 x 12 for the
// triangles, and the text; building 2 x 212 + 4 x 64.
TEST_F(ObjFiles, TextureCoordinatesCountInTheMemoryCheck) {
  constexpr std::string_view kText =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n";
  const uint64_t needed = kText.size() + 4 * 48 + 4 * 8 + 4 * 8 + 1 + 2 * 12 + 2 * 212 + 4 * 64;
  const std::string path = write("quad.obj", kText);
  EXPECT_EQ(loadObjModel(path, kReferencedFrom, {needed, "test"}).triangleCount(), 2u);
  EXPECT_THROW(loadObjModel(path, kReferencedFrom, {needed - 1, "test"}), SceneError);
}

const BadObj kBadTextureCoordinates[] = {
    {"texture_index_out_of_range", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/2\n", 5, 11,
     "face refers to texture coordinate 2 but the file has 1"},
    {"relative_texture_index_out_of_range", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/-2 2/1 3/1\n",
     5, 3, "face refers to texture coordinate -2 but only 1 come before it"},
    {"texture_index_without_coordinates", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/1 3/1\n", 4, 3,
     "face refers to texture coordinate 1 but the file has 0"},
    {"empty_texture_coordinate", "vt\nv 0 0 0\n", 1, 1, "texture coordinate needs 1 coordinate"},
    {"letter_texture_coordinate", "vt 0 q\n", 1, 6, "expected a number but found 'q'"},
    {"huge_texture_coordinate", "vt 1e40 0\n", 1, 4, "non-finite coordinate"},
};

INSTANTIATE_TEST_SUITE_P(TextureCoordinates, ObjBadInput, testing::ValuesIn(kBadTextureCoordinates),
                         [](const testing::TestParamInfo<BadObj>& info) {
                           return std::string(info.param.name);
                         });

}  // namespace
}  // namespace prism
