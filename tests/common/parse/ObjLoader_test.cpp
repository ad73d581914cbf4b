#include "parse/ObjLoader.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string_view>

namespace prism {
namespace {

namespace fs = std::filesystem;
using namespace std::string_view_literals;

const FileLoc kReferencedFrom{"scene.yaml", 7, 11};

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
  const MeshDesc mesh = loadObjMesh(objPath("cube_normals.obj"), kReferencedFrom);
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
  const MeshDesc mesh = loadObjMesh(objPath("quad.obj"), kReferencedFrom);
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
  const MeshDesc mesh = loadObjMesh(path, kReferencedFrom);
  EXPECT_EQ(mesh.triangleCount(), 2u);
  EXPECT_TRUE(mesh.normals.empty());
  EXPECT_EQ(mesh.positions.size(), 4u);  // shared corners are shared again once normals go
}

TEST_F(ObjFiles, ZeroNormalMakesTheMeshFlat) {
  const std::string path =
      write("zero_normal.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 0\nf 1//1 2//1 3//1\n");
  EXPECT_TRUE(loadObjMesh(path, kReferencedFrom).normals.empty());
}

TEST(ObjLoader, NormalsTooSmallOrTooLargeToNormaliseMakeTheMeshFlat) {
  for (const char* normal : {"1e-30 1e-30 1e-30", "1e30 1e30 1e30", "1e-45 0 0"}) {
    std::string text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn ";
    text += normal;
    text += "\nf 1//1 2//1 3//1\n";
    EXPECT_TRUE(parseObjMesh(text, "mem.obj", {}).normals.empty()) << normal;
  }
  const MeshDesc tiny =
      parseObjMesh("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1e-20\nf 1//1 2//1 3//1\n", "m.obj", {});
  ASSERT_EQ(tiny.normals.size(), 3u);  // small, but its length is a normal float
  EXPECT_NEAR(tiny.normals[0].z, 1.0f, 1e-5f);
}

TEST_F(ObjFiles, ConcaveFaceIsEarClipped) {
  // An L-shaped hexagon with texture coordinates and relative (negative) indices.
  const std::string path = write("l_shape.obj",
                                 "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\n"
                                 "vt 0 0\nf -6/1 -5/1 -4/1 -3/1 -2/1 -1/1\n");
  const MeshDesc mesh = loadObjMesh(path, kReferencedFrom);
  EXPECT_EQ(mesh.triangleCount(), 4u);
  EXPECT_FLOAT_EQ(meshArea(mesh), 3.0f);
  for (size_t t = 0; t < 4; ++t) EXPECT_GT(geometricNormal(mesh, t).z, 0.0f);
}

TEST(ObjLoader, TextInMemoryLoadsLikeTheFileAndErrorsNameThePath) {
  const MeshDesc mesh =
      parseObjMesh("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n", "mem.obj", kReferencedFrom);
  EXPECT_EQ(mesh.source, "mem.obj");
  EXPECT_EQ(mesh.triangleCount(), 2u);
  EXPECT_FLOAT_EQ(meshArea(mesh), 1.0f);
  try {
    parseObjMesh("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "mem.obj", kReferencedFrom);
    FAIL() << "expected a SceneError";
  } catch (const SceneError& error) {
    EXPECT_EQ(error.loc().file, "mem.obj");
    EXPECT_EQ(error.loc().line, 4);
    EXPECT_EQ(error.message(), "face refers to vertex 9 but the file has 3");
  }
}

TEST(ObjLoader, MissingFileIsReportedWhereTheSceneNamesIt) {
  try {
    loadObjMesh("no/such/mesh.obj", kReferencedFrom);
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
    loadObjMesh(dir_.string(), kReferencedFrom);
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
    loadObjMesh(path, kReferencedFrom);
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
  EXPECT_EQ(loadObjMesh(path, kReferencedFrom, {891, "test"}).triangleCount(), 2u);
  try {
    loadObjMesh(path, kReferencedFrom, {890, "test"});
    FAIL() << "expected a refusal";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              "scene.yaml:7:11: mesh file '" + path +
                  "' (2 triangles, 4 vertices) read and built needs 891 B (891 bytes); the "
                  "memory limit is 890 B (890 bytes, test): simplify the mesh or raise "
                  "--memory-limit");
  }
  try {  // smaller than the file itself: refused before a byte is read
    loadObjMesh(path, kReferencedFrom, {41, "test"});
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
  return a.positions == b.positions && a.normals == b.normals && a.indices == b.indices;
}

// Every line ending, relative indices, normals, a polygon, comments and skipped statements.
constexpr std::string_view kEverything =
    "# header\r\nmtllib none.mtl\nv 0 0 0\r\nv 2 0 0\rv 2 1 0\nv 1 1 0\n\nv 1 2 0\n"
    "v 0 2 0 # six\nvn 0 0 3\r\nvt 0 0\ng part\nusemtl x\ns 1\n"
    "f -6/1/1 -5/1/1 -4/1/1 -3/1/1 -2/1/1 -1/1/1\r\n"
    "vn 0 0 2\nf 1//-2 2//-2 6//1 # a triangle\n  \t f 4//1 5//1 6//1";

TEST(ObjLoader, TheMeshIsTheSameHoweverTheTextIsCutForTheThreads) {
  const MeshDesc whole = parseObjMesh(kEverything, "mem.obj", kReferencedFrom);
  EXPECT_EQ(whole.triangleCount(), 4u + 1u + 1u);
  EXPECT_EQ(whole.positions.size(), 6u);  // one normal per position: no position doubles
  ASSERT_EQ(whole.normals.size(), 6u);
  for (const Vec3& n : whole.normals) EXPECT_EQ(n, Vec3(0, 0, 1));  // normalised
  EXPECT_FLOAT_EQ(meshArea(whole), 3.0f + 2.0f + 0.5f);
  for (size_t piece = 1; piece <= kEverything.size(); ++piece) {
    const MeshDesc cut = parseObjMesh(kEverything, "mem.obj", kReferencedFrom, {}, piece);
    EXPECT_TRUE(sameMesh(cut, whole)) << "pieces of " << piece << " bytes";
  }
}

TEST(ObjLoader, TheFirstErrorIsFoundHoweverTheTextIsCut) {
  // Line 6 has the first error; line 8 has another.
  const std::string text = "v 0 0 0\r\nv 1 0 0\rv 0 1 0\n# ok\nf 1 2 3\nf 1 2 -9\nv x 0 0\n";
  for (size_t piece = 1; piece <= text.size(); ++piece) {
    try {
      parseObjMesh(text, "mem.obj", kReferencedFrom, {}, piece);
      ADD_FAILURE() << "no error with pieces of " << piece << " bytes";
    } catch (const SceneError& error) {
      EXPECT_EQ(error.loc().line, 6) << "pieces of " << piece << " bytes";
      EXPECT_EQ(error.loc().column, 7) << "pieces of " << piece << " bytes";
      EXPECT_EQ(error.message(), "face refers to vertex -9 but only 3 come before it");
    }
  }
}

TEST(ObjLoader, FacesMayNameVerticesThatComeLater) {
  const MeshDesc mesh = parseObjMesh("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", "mem.obj", {});
  EXPECT_EQ(mesh.triangleCount(), 1u);
  EXPECT_EQ(mesh.positions[1], Vec3(1, 0, 0));
}

TEST(ObjLoader, UnusedVerticesAreDroppedAndTheRestNumberedInTheOrderFacesUseThem) {
  const MeshDesc mesh =
      parseObjMesh("v 9 9 9\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 4 2 3\n", "mem.obj", {});
  EXPECT_EQ(mesh.positions, (std::vector<Vec3>{{0, 1, 0}, {0, 0, 0}, {1, 0, 0}}));
  EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2}));
}

TEST(ObjLoader, APositionWithTwoNormalsBecomesTwoVertices) {
  const MeshDesc mesh = parseObjMesh(
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
      EXPECT_EQ(parseObjMesh(text, "mem.obj", {}).triangleCount(), 253u);
    } else {
      try {
        parseObjMesh(text, "mem.obj", {});
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
