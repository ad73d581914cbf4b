#include "parse/PlyLoader.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "image/ToneMap.h"
#include "parse/ModelFile.h"

namespace prism {
namespace {

namespace fs = std::filesystem;

const FileLoc kReferencedFrom{"scene.yaml", 3, 9};

// A PLY body written value by value, in either byte order.
class BinaryWriter {
 public:
  explicit BinaryWriter(bool bigEndian) : bigEndian_(bigEndian) {}
  template <class T>
  BinaryWriter& put(T value) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    if (bigEndian_ != (std::endian::native == std::endian::big)) {
      for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
    }
    text_.append(bytes, sizeof(T));
    return *this;
  }
  const std::string& text() const { return text_; }

 private:
  bool bigEndian_;
  std::string text_;
};

// A unit cube's eight corners and its six faces as quads (outward, counter-clockwise), with
// colours and an edge element to be read past, and a double normal per vertex.
constexpr float kCorners[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                  {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
constexpr int kQuads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                              {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};

std::string cubeHeader(const char* format) {
  return std::string("ply\nformat ") + format +
         " 1.0\ncomment a cube\nelement vertex 8\nproperty float x\nproperty uchar red\n"
         "property float y\nproperty float z\nproperty double nx\nproperty double ny\n"
         "property double nz\nelement edge 1\nproperty int vertex1\nproperty int vertex2\n"
         "element face 6\nproperty list uchar float texcoord\n"
         "property list uchar int vertex_indices\nend_header\n";
}

Vec3 outward(int corner) {
  return Vec3(kCorners[corner][0], kCorners[corner][1], kCorners[corner][2]) - Vec3(0.5f);
}

std::string asciiCube() {
  std::string text = cubeHeader("ascii");
  for (int v = 0; v < 8; ++v) {
    const Vec3 n = outward(v);
    text += std::to_string(kCorners[v][0]) + " 200 " + std::to_string(kCorners[v][1]) + " " +
            std::to_string(kCorners[v][2]) + "  " + std::to_string(n.x) + " " +
            std::to_string(n.y) + " " + std::to_string(n.z) + "\r\n";
  }
  text += "0 1\n";
  for (const auto& quad : kQuads) {
    text += "2 0.5 0.5 4";
    for (int c : quad) {
      text += ' ';
      text += std::to_string(c);
    }
    text += "\n";
  }
  return text;
}

std::string binaryCube(bool bigEndian) {
  BinaryWriter body(bigEndian);
  for (int v = 0; v < 8; ++v) {
    const Vec3 n = outward(v);
    body.put(kCorners[v][0]).put(uint8_t{200}).put(kCorners[v][1]).put(kCorners[v][2]);
    body.put(double{n.x}).put(double{n.y}).put(double{n.z});
  }
  body.put(int32_t{0}).put(int32_t{1});
  for (const auto& quad : kQuads) {
    body.put(uint8_t{2}).put(0.5f).put(0.5f).put(uint8_t{4});
    for (int c : quad) body.put(int32_t{c});
  }
  return cubeHeader(bigEndian ? "binary_big_endian" : "binary_little_endian") + body.text();
}

float meshArea(const MeshDesc& mesh) {
  float area = 0.0f;
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    const Vec3& a = mesh.positions[mesh.indices[3 * t]];
    area += 0.5f * glm::length(glm::cross(mesh.positions[mesh.indices[3 * t + 1]] - a,
                                          mesh.positions[mesh.indices[3 * t + 2]] - a));
  }
  return area;
}

TEST(PlyLoader, AsciiCubeQuadsBecomeFansWithNormalisedNormals) {
  const MeshDesc mesh = parsePlyMesh(asciiCube(), "cube.ply", kReferencedFrom);
  EXPECT_EQ(mesh.source, "cube.ply");
  ASSERT_EQ(mesh.positions.size(), 8u);
  for (int v = 0; v < 8; ++v) {
    EXPECT_EQ(mesh.positions[v], Vec3(kCorners[v][0], kCorners[v][1], kCorners[v][2]));
    EXPECT_NEAR(glm::length(mesh.normals[v]), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(mesh.normals[v], glm::normalize(outward(v))), 1.0f, 1e-6f);
  }
  ASSERT_EQ(mesh.triangleCount(), 12u);
  // The first quad (0 3 2 1) as a fan: (0 3 2), (0 2 1).
  EXPECT_EQ(std::vector<uint32_t>(mesh.indices.begin(), mesh.indices.begin() + 6),
            (std::vector<uint32_t>{0, 3, 2, 0, 2, 1}));
  EXPECT_FLOAT_EQ(meshArea(mesh), 6.0f);
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {  // every fan triangle faces outward
    const Vec3& a = mesh.positions[mesh.indices[3 * t]];
    const Vec3 n = glm::cross(mesh.positions[mesh.indices[3 * t + 1]] - a,
                              mesh.positions[mesh.indices[3 * t + 2]] - a);
    EXPECT_GT(glm::dot(n, a + mesh.positions[mesh.indices[3 * t + 2]] - Vec3(1.0f)), 0.0f) << t;
  }
}

TEST(PlyLoader, BinaryCubesInBothByteOrdersReadAsTheAsciiOne) {
  const MeshDesc ascii = parsePlyMesh(asciiCube(), "cube.ply", kReferencedFrom);
  for (const bool bigEndian : {false, true}) {
    const MeshDesc binary = parsePlyMesh(binaryCube(bigEndian), "cube.ply", kReferencedFrom);
    EXPECT_EQ(binary.positions, ascii.positions) << bigEndian;
    EXPECT_EQ(binary.indices, ascii.indices) << bigEndian;
    ASSERT_EQ(binary.normals.size(), 8u);
    for (int v = 0; v < 8; ++v) {
      EXPECT_NEAR(glm::dot(binary.normals[v], ascii.normals[v]), 1.0f, 1e-6f) << bigEndian;
    }
  }
}

// Enough triangles that the binary reader takes them in several blocks on several threads.
struct ManyTriangles {
  static constexpr int kVertices = 1000;
  static constexpr int kFaces = 3 * 65536 + 5;

  static std::string header(const char* format, int faces = kFaces) {
    return std::string("ply\nformat ") + format + " 1.0\nelement vertex " +
           std::to_string(kVertices) +
           "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
           std::to_string(faces) + "\nproperty list uchar uint vertex_indices\nend_header\n";
  }
  static Vec3 vertex(int v) { return Vec3(0.25f * static_cast<float>(v), 1.0f / (1 + v), -0.5f); }
  static uint32_t corner(int f, int c) {
    return static_cast<uint32_t>((f * 7 + c * 131) % kVertices);
  }

  // The faces as triangles, one (the quad) with a fourth corner, one (bad) with a corner out of
  // range.
  static std::string file(bool binary, int quad = -1, int bad = -1) {
    BinaryWriter body(false);
    std::string text;
    for (int v = 0; v < kVertices; ++v) {
      const Vec3 p = vertex(v);
      body.put(p.x).put(p.y).put(p.z);
      text += std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
    }
    for (int f = 0; f < kFaces; ++f) {
      const int corners = f == quad ? 4 : 3;
      body.put(static_cast<uint8_t>(corners));
      text += std::to_string(corners);
      for (int c = 0; c < corners; ++c) {
        const uint32_t index = f == bad && c == 2 ? kVertices : corner(f, c);
        body.put(index);
        text += ' ';
        text += std::to_string(index);
      }
      text += "\n";
    }
    return binary ? header("binary_little_endian") + body.text() : header("ascii") + text;
  }
};

TEST(PlyLoader, ManyBinaryTrianglesReadAsTheirAsciiText) {
  const MeshDesc binary = parsePlyMesh(ManyTriangles::file(true), "many.ply", {});
  ASSERT_EQ(binary.triangleCount(), static_cast<size_t>(ManyTriangles::kFaces));
  for (int v = 0; v < ManyTriangles::kVertices; ++v) {
    ASSERT_EQ(binary.positions[v], ManyTriangles::vertex(v)) << v;
  }
  for (int f = 0; f < ManyTriangles::kFaces; ++f) {
    for (int c = 0; c < 3; ++c) ASSERT_EQ(binary.indices[3 * f + c], ManyTriangles::corner(f, c));
  }
  // A quad among them: read one by one, split into two triangles, the rest as before.
  const int quad = 2 * 65536 + 17;
  const MeshDesc withQuad = parsePlyMesh(ManyTriangles::file(true, quad), "many.ply", {});
  ASSERT_EQ(withQuad.triangleCount(), binary.triangleCount() + 1);
  EXPECT_EQ(withQuad.indices[3 * quad + 3], ManyTriangles::corner(quad, 0));
  EXPECT_EQ(withQuad.indices[3 * quad + 5], ManyTriangles::corner(quad, 3));
  EXPECT_EQ(parsePlyMesh(ManyTriangles::file(false, quad), "many.ply", {}).indices,
            withQuad.indices);
}

TEST(PlyLoader, TheFirstBadFaceAmongManyIsNamedWithItsByte) {
  const int bad = 65536 + 3;
  const std::string header = ManyTriangles::header("binary_little_endian");
  try {
    parsePlyMesh(ManyTriangles::file(true, -1, bad), "many.ply", {});
    FAIL() << "a face out of range was read";
  } catch (const SceneError& e) {
    // The third index of the face: header, vertices, the faces before, its length and two indices.
    const size_t byte = header.size() + 12 * ManyTriangles::kVertices + 13 * bad + 1 + 8 + 4;
    EXPECT_EQ(e.message(), "face " + std::to_string(bad) + " (byte " + std::to_string(byte) +
                               "): face refers to vertex 1000 but the file has 1000 (counted "
                               "from 0)");
  }
}

TEST(PlyLoader, AZeroNormalOrAMissingComponentLeavesTheMeshFlat) {
  const std::string zero =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
      "element face 1\nproperty list uchar uint vertex_index\nend_header\n"
      "0 0 0 0 0 1\n1 0 0 0 0 0\n0 1 0 0 0 1\n3 0 1 2\n";
  EXPECT_TRUE(parsePlyMesh(zero, "z.ply", {}).normals.empty());
  const std::string partial =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty float nz\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n0 0 0 1\n1 0 0 1\n0 1 0 1\n3 0 1 2\n";
  const MeshDesc mesh = parsePlyMesh(partial, "p.ply", {});
  EXPECT_TRUE(mesh.normals.empty());
  EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2}));
}

struct BadPly {
  const char* name;
  std::string text;
  int line;  // 0: the error names the file only
  int column;
  const char* message;
};

const std::string kTriangleHeader =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";

std::vector<BadPly> badPlyFiles() {
  std::string truncated = binaryCube(false);
  truncated.resize(truncated.size() - 3);
  std::string nanVertex = cubeHeader("binary_little_endian");
  BinaryWriter body(false);
  body.put(0.0f).put(uint8_t{0}).put(std::numeric_limits<float>::quiet_NaN());
  nanVertex += body.text() + std::string(400, '\0');
  return {
      {"obj_text", "v 0 0 0\n", 1, 1, "not a PLY file: it must start with a line 'ply'"},
      {"unknown_format", "ply\nformat binary_middle_endian 1.0\nend_header\n", 2, 8,
       "unknown format 'binary_middle_endian'"},
      {"no_end_header", "ply\nformat ascii 1.0\nelement vertex 0\n", 4, 1,
       "the header has no 'end_header' line"},
      {"no_format", "ply\nelement vertex 0\nend_header\n", 3, 1, "no 'format' line"},
      {"property_first", "ply\nformat ascii 1.0\nproperty float x\nend_header\n", 3, 1,
       "a property before any element"},
      {"unknown_type", "ply\nformat ascii 1.0\nelement vertex 1\nproperty half x\nend_header\n", 4,
       10, "unknown type 'half'"},
      {"float_list_length",
       "ply\nformat ascii 1.0\nelement face 1\nproperty list float int vertex_indices\n"
       "end_header\n",
       4, 15, "expected an integer type for a list's length"},
      {"absurd_count",
       "ply\nformat binary_little_endian 1.0\nelement vertex 100000000000000\n"
       "property float x\nproperty float y\nproperty float z\nend_header\n\x01\x02",
       3, 1, "element 'vertex' declares 100000000000000 but the 2-byte body cannot hold"},
      {"no_face", "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nend_header\n", 0, 0,
       "the file has no 'face' element"},
      {"no_z",
       "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
       "element face 0\nproperty list uchar int vertex_indices\nend_header\n0 0\n",
       3, 1, "the vertex element has no 'z' property"},
      {"letter_in_vertex", kTriangleHeader + "0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n", 11, 3,
       "vertex 1: expected a number but found 'x'"},
      {"index_out_of_range", kTriangleHeader + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", 13, 7,
       "face 0: face refers to vertex 3 but the file has 3 (counted from 0)"},
      {"two_corner_face", kTriangleHeader + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n", 13, 1,
       "face 0: a face needs at least 3 vertices but this one has 2"},
      {"count_past_its_type", kTriangleHeader + "0 0 0\n1 0 0\n0 1 0\n300 0 1 2\n", 13, 1,
       "face 0: expected an integer of the declared type but found '300'"},
      {"ascii_ends_early", kTriangleHeader + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n", 14, 1,
       "face 0: the file ends inside it"},
      {"binary_ends_early", truncated, 0, 0, "face 5 (byte "},
      {"nan_vertex", nanVertex, 0, 0, "vertex 0 (byte "},
      {"no_triangles",
       "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
       "property float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n",
       0, 0, "mesh file has no triangles"},
  };
}

class PlyBadInput : public testing::TestWithParam<BadPly> {};

TEST_P(PlyBadInput, FailsWithWhereAndWhat) {
  const BadPly& bad = GetParam();
  try {
    parsePlyMesh(bad.text, "bad.ply", kReferencedFrom);
    FAIL() << bad.name << " loaded without error";
  } catch (const SceneError& error) {
    EXPECT_EQ(error.loc().file, "bad.ply") << error.what();
    EXPECT_EQ(error.loc().line, bad.line) << error.what();
    if (bad.line > 0) {
      EXPECT_EQ(error.loc().column, bad.column) << error.what();
    }
    EXPECT_NE(error.message().find(bad.message), std::string::npos) << error.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Ply, PlyBadInput, testing::ValuesIn(badPlyFiles()),
                         [](const testing::TestParamInfo<BadPly>& info) {
                           return std::string(info.param.name);
                         });

TEST(PlyLoader, TheSmallestAsciiBodyIsNotTakenForATruncatedOne) {
  // Nine one-character values, single spaces, no line end after the last: 17 bytes, the fewest
  // three vertices can take. The header check lets them through; the reader then finds no face.
  const std::string text =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 1 0 0 0 1 0";
  try {
    parsePlyMesh(text, "t.ply", {});
    FAIL() << "a mesh without faces loaded";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.message(), "mesh file has no triangles");
  }
}

TEST(PlyLoader, AMeshPastTheMemoryLimitIsRefusedBeforeItsArraysExist) {
  const std::string text = kTriangleHeader + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  // Reading: the file + 3 x 12 + 1 x 12; building: 1 x 212 + 3 x 64.
  const uint64_t needed = text.size() + 36 + 12 + 212 + 192;
  EXPECT_EQ(parsePlyMesh(text, "t.ply", kReferencedFrom, {needed, "test"}).triangleCount(), 1u);
  try {
    parsePlyMesh(text, "t.ply", kReferencedFrom, {needed - 1, "test"});
    FAIL() << "expected a refusal";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.loc().file, "scene.yaml");
    EXPECT_NE(e.message().find("mesh file 't.ply' (at least 1 triangles, 3 vertices) read and "
                               "built needs"),
              std::string::npos)
        << e.what();
  }
}

// A triangle whose vertices carry texture coordinates and colours under the names given, as
// ASCII or binary (little or big endian).
struct AttributeTriangle {
  const char* uvType;  // "float", "double"
  const char* uName;
  const char* vName;
  const char* colourType;  // "uchar", "ushort", "float"

  std::string header(const char* format) const {
    return std::string("ply\nformat ") + format +
           " 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
           "property " +
           uvType + " " + uName + "\nproperty " + uvType + " " + vName + "\nproperty " +
           colourType + " red\nproperty " + colourType + " green\nproperty " + colourType +
           " blue\nproperty uchar alpha\nelement face 1\n"
           "property list uchar int vertex_indices\nend_header\n";
  }
  // Vertex i's texture coordinate, and its colour as the file holds it (integer types: the
  // type's share; floats: linear).
  static Vec2 uv(int i) {
    return Vec2(0.25f * static_cast<float>(i), 1.0f - 0.5f * static_cast<float>(i));
  }
  static uint32_t level(int i, int channel) { return static_cast<uint32_t>(40 * i + 70 * channel); }

  std::string file(const char* format, bool bigEndian = false) const {
    const std::string type = colourType;
    if (std::string(format) == "ascii") {
      std::string text = header(format);
      for (int i = 0; i < 3; ++i) {
        text += std::to_string(i % 2) + " " + std::to_string(i / 2) + " 0 " +
                std::to_string(uv(i).x) + " " + std::to_string(uv(i).y);
        for (int c = 0; c < 3; ++c) {
          text += " ";
          text += type == "float" ? std::to_string(static_cast<float>(level(i, c)) / 255.0f)
                                  : std::to_string(level(i, c) * (type == "ushort" ? 257 : 1));
        }
        text += " 255\n";
      }
      return text + "3 0 1 2\n";
    }
    BinaryWriter body(bigEndian);
    for (int i = 0; i < 3; ++i) {
      body.put(static_cast<float>(i % 2)).put(static_cast<float>(i / 2)).put(0.0f);
      if (std::string(uvType) == "double") {
        body.put(double{uv(i).x}).put(double{uv(i).y});
      } else {
        body.put(uv(i).x).put(uv(i).y);
      }
      for (int c = 0; c < 3; ++c) {
        if (type == "uchar") body.put(static_cast<uint8_t>(level(i, c)));
        if (type == "ushort") body.put(static_cast<uint16_t>(level(i, c) * 257));
        if (type == "float") body.put(static_cast<float>(level(i, c)) / 255.0f);
      }
      body.put(uint8_t{255});
    }
    body.put(uint8_t{3}).put(int32_t{0}).put(int32_t{1}).put(int32_t{2});
    return header(format) + body.text();
  }

  void expectRead(const MeshDesc& mesh, const std::string& what) const {
    SCOPED_TRACE(what);
    ASSERT_EQ(mesh.uvs.size(), 3u);
    ASSERT_EQ(mesh.colors.size(), 3u);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(mesh.uvs[i].x, uv(i).x, 1e-6f);
      EXPECT_NEAR(mesh.uvs[i].y, uv(i).y, 1e-6f);
      for (int c = 0; c < 3; ++c) {
        const float share = static_cast<float>(level(i, c)) / 255.0f;
        // Integers are sRGB-encoded; floats are linear as they stand.
        const float linear = std::string(colourType) == "float" ? share : srgbToLinear(share);
        EXPECT_NEAR(mesh.colors[i][c], linear, 1e-5f) << "vertex " << i << " channel " << c;
      }
    }
  }
};

TEST(PlyLoader, TextureCoordinatesAndColoursAreReadFromEveryFormat) {
  const AttributeTriangle kinds[] = {{"float", "u", "v", "uchar"},
                                     {"float", "s", "t", "float"},
                                     {"double", "texture_u", "texture_v", "ushort"},
                                     {"float", "texture_s", "texture_t", "uchar"}};
  for (const AttributeTriangle& kind : kinds) {
    const std::string what = std::string(kind.uName) + " " + kind.colourType;
    kind.expectRead(parsePlyMesh(kind.file("ascii"), "a.ply", {}), what + " ascii");
    kind.expectRead(parsePlyMesh(kind.file("binary_little_endian"), "b.ply", {}),
                    what + " little endian");
    kind.expectRead(parsePlyMesh(kind.file("binary_big_endian", true), "b.ply", {}),
                    what + " big endian");
  }
}

TEST(PlyLoader, AColourByteIsDecodedThroughTheSrgbCurve) {
  const AttributeTriangle kind{"float", "u", "v", "uchar"};
  const MeshDesc mesh = parsePlyMesh(kind.file("binary_little_endian"), "b.ply", {});
  // Vertex 2, green: byte 150 is 0.3049 linear (sRGB), not 150/255 = 0.588.
  EXPECT_NEAR(mesh.colors[2].g, 0.30499f, 1e-4f);
}

TEST(PlyLoader, PartialTextureCoordinatesOrColoursAreNotKept) {
  const std::string text =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty float u\nproperty uchar red\nproperty uchar green\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 0.5 1 2\n1 0 0 0.5 1 2\n0 1 0 0.5 1 2\n3 0 1 2\n";
  const MeshDesc mesh = parsePlyMesh(text, "p.ply", {});
  EXPECT_TRUE(mesh.uvs.empty());
  EXPECT_TRUE(mesh.colors.empty());
  EXPECT_EQ(mesh.triangleCount(), 1u);
}

TEST(PlyLoader, NegativeOrNonFiniteAttributesAreNamed) {
  const AttributeTriangle kind{"float", "u", "v", "float"};
  std::string binary = kind.file("binary_little_endian");
  // Vertex 1's blue: after the header, vertex 0 (5 floats, 3 floats, a byte) and vertex 1's
  // first seven floats.
  const size_t at = kind.header("binary_little_endian").size() + 33 + 7 * 4;
  const float negative = -0.5f;
  std::memcpy(&binary[at], &negative, 4);
  try {
    parsePlyMesh(binary, "b.ply", {});
    FAIL() << "a negative colour was read";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.message(),
              "vertex 1 (byte " + std::to_string(at + 4) + "): negative colour 'blue'");
  }
  const float nan = std::nanf("");
  std::memcpy(&binary[at - 12], &nan, 4);  // vertex 1's v
  try {
    parsePlyMesh(binary, "b.ply", {});
    FAIL() << "a non-finite texture coordinate was read";
  } catch (const SceneError& e) {
    EXPECT_NE(e.message().find("non-finite 'v'"), std::string::npos) << e.what();
  }
}

TEST(ModelFile, PlyFilesGoToThePlyReaderWhateverTheCaseOfTheirName) {
  const fs::path dir = fs::temp_directory_path() / ("prism_ply_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string path = (dir / "Cube.PLY").string();
  std::ofstream(path, std::ios::binary) << binaryCube(true);
  const ModelDesc model = loadModelFile(path, kReferencedFrom);
  ASSERT_EQ(model.meshes.size(), 1u);
  const MeshDesc& mesh = model.meshes[0];
  EXPECT_EQ(mesh.triangleCount(), 12u);
  EXPECT_EQ(mesh.source, path);
  try {
    loadModelFile((dir / "missing.ply").string(), kReferencedFrom);
    ADD_FAILURE() << "a missing file loaded";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.loc().file, "scene.yaml");
    EXPECT_NE(e.message().find("No such file or directory"), std::string::npos);
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace prism
