#include "parse/GltfLoader.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/parse/GltfAssets.h"
#include "image/PngFile.h"
#include "parse/GltfScene.h"
#include "parse/ModelFile.h"

namespace prism {
namespace {

namespace fs = std::filesystem;
using gltftest::GltfAssets;
using gltftest::parse;

// A 2×2 checker as PNG bytes: red, green on the top row; blue, white below.
std::string checkerPng() {
  const uint8_t rgb[12] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};
  const fs::path file =
      fs::temp_directory_path() / ("prism_gltf_checker_" + std::to_string(::getpid()) + ".png");
  writePng(file.string(), 2, 2, rgb, {});
  std::ifstream in(file, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  fs::remove(file);
  return bytes.str();
}

// A unit box, four vertices per face (uv (0,0) (1,0) (1,1) (0,1) in glTF's top-down v), with
// normals and u16 indices, its base colour a texture whose image is `image` (JSON).
std::string texturedBox(GltfAssets& a, const std::string& image) {
  std::vector<float> p, n, uv;
  std::vector<uint16_t> idx;
  const float corners[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side < 2; ++side) {
      const uint16_t base = static_cast<uint16_t>(p.size() / 3);
      for (const auto& c : corners) {
        float v[3];
        v[axis] = static_cast<float>(side);
        v[(axis + 1) % 3] = side ? c[0] : c[1];
        v[(axis + 2) % 3] = side ? c[1] : c[0];
        p.insert(p.end(), v, v + 3);
        float normal[3] = {0, 0, 0};
        normal[axis] = side ? 1.0f : -1.0f;
        n.insert(n.end(), normal, normal + 3);
        uv.insert(uv.end(), c, c + 2);
      }
      for (uint16_t k : {0, 1, 2, 0, 2, 3}) idx.push_back(static_cast<uint16_t>(base + k));
    }
  }
  const int pa = a.floats(p, "VEC3", 3), na = a.floats(n, "VEC3", 3), ua = a.floats(uv, "VEC2", 2);
  const int ia = a.indices(idx);
  return "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{"
         "\"attributes\":{\"POSITION\":" +
         std::to_string(pa) + ",\"NORMAL\":" + std::to_string(na) +
         ",\"TEXCOORD_0\":" + std::to_string(ua) + "},\"indices\":" + std::to_string(ia) +
         ",\"material\":0}]}],\"materials\":[{\"name\":\"checker\",\"pbrMetallicRoughness\":{"
         "\"baseColorTexture\":{\"index\":0},\"metallicFactor\":0}}],\"textures\":[{\"source\":0}],"
         "\"images\":[" +
         image + "]";
}

void expectCheckerBox(const ModelDesc& model) {
  ASSERT_EQ(model.meshes.size(), 1u);
  const MeshDesc& mesh = model.meshes[0];
  EXPECT_EQ(mesh.triangleCount(), 12u);
  ASSERT_EQ(mesh.positions.size(), 24u);
  ASSERT_EQ(mesh.uvs.size(), 24u);
  ASSERT_EQ(mesh.normals.size(), 24u);
  // glTF's (0, 0) is the image's top-left texel; Prism's v counts from the bottom.
  EXPECT_EQ(mesh.uvs[0], Vec2(0.0f, 1.0f));
  EXPECT_EQ(mesh.uvs[2], Vec2(1.0f, 0.0f));
  ASSERT_EQ(model.materials.size(), 1u);
  ASSERT_TRUE(model.materials[0].diffuseMap);
  const TextureMap& map = *model.materials[0].diffuseMap;
  EXPECT_EQ(map.scale, Vec2(1.0f));
  EXPECT_NEAR(map.offset.x, 0.0f, 1e-6f);
  EXPECT_NEAR(map.offset.y, 0.0f, 1e-6f);
  EXPECT_EQ(map.rotation, 0.0f);
  ASSERT_EQ(model.textures.size(), 1u);
  const SrgbImage& image = model.textures[map.texture].srgb;
  ASSERT_EQ(image.width, 2);
  EXPECT_EQ(image.rgb, (std::vector<uint8_t>{255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255}));
  EXPECT_EQ(model.materials[0].diffuse, Color(1.0f));
}

TEST(GltfLoader, ACheckerBoxReadsAlikeFromADataUriAGlbAndExternalFiles) {
  const std::string png = checkerPng();
  {
    GltfAssets a;
    const std::string body =
        texturedBox(a, "{\"uri\":\"data:image/png;base64," + gltftest::base64(png) + "\"}");
    expectCheckerBox(parse(a.gltf(body)));
  }
  {
    GltfAssets a;
    const std::string body = texturedBox(a, "{\"bufferView\":@,\"mimeType\":\"image/png\"}");
    const int view = a.view(png);
    std::string withView = body;
    withView.replace(withView.find('@'), 1, std::to_string(view));
    expectCheckerBox(parse(a.glb(withView), "model.glb"));
  }
  const fs::path dir = fs::temp_directory_path() / ("prism_gltf_" + std::to_string(::getpid()));
  fs::create_directories(dir / "tex");
  GltfAssets a;
  const std::string json = a.json(texturedBox(a, "{\"uri\":\"tex/check%20er.png\"}"), "box.bin");
  std::ofstream(dir / "box.gltf") << json;
  std::ofstream(dir / "box.bin", std::ios::binary) << a.bin;
  std::ofstream(dir / "tex" / "check er.png", std::ios::binary) << png;
  const ModelDesc model = loadModelFile((dir / "box.gltf").string(), {});
  expectCheckerBox(model);
  EXPECT_EQ(model.textures[0].path, (dir / "tex/check er.png").string());
  fs::remove(dir / "box.bin");
  try {
    loadGltfModel((dir / "box.gltf").string(), {});
    ADD_FAILURE() << "a missing .bin was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "box.gltf: buffers[0].uri: the buffer file 'box.bin' is missing"),
              std::string::npos)
        << e.what();
  }
  fs::remove_all(dir);
}

TEST(GltfLoader, TheBaseColourTexturesTransformIsRead) {
  GltfAssets a;
  std::string body =
      texturedBox(a, "{\"uri\":\"data:image/png;base64," + gltftest::base64(checkerPng()) + "\"}");
  const std::string plain = "\"baseColorTexture\":{\"index\":0}";
  body.replace(body.find(plain), plain.size(),
               "\"baseColorTexture\":{\"index\":0,\"extensions\":{\"KHR_texture_transform\":"
               "{\"offset\":[0.5,0.25],\"rotation\":1.5707963,\"scale\":[2,3]}}}");
  const ModelDesc model = parse(a.gltf(body));
  ASSERT_TRUE(model.materials[0].diffuseMap);
  const TextureMap& map = *model.materials[0].diffuseMap;
  // Rotation −θ, the same scale, offset (oᵤ − s_v·sin θ, 1 − o_v − s_v·cos θ).
  EXPECT_NEAR(map.rotation, -1.5707963f, 1e-6f);
  EXPECT_EQ(map.scale, Vec2(2.0f, 3.0f));
  EXPECT_NEAR(map.offset.x, 0.5f - 3.0f, 1e-5f);
  EXPECT_NEAR(map.offset.y, 0.75f, 1e-5f);
}

TEST(GltfLoader, TriangleStripsAndFansBecomeListsWithTheirWinding) {
  GltfAssets a;
  const int p = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 2, 1, 0}, "VEC3", 3);
  const int strip = a.indices({0, 1, 2, 3, 4});
  const int fan = a.indices32({0, 1, 3, 2});
  const std::string body =
      "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":" +
      std::to_string(p) + "},\"indices\":" + std::to_string(strip) +
      ",\"mode\":5},{\"attributes\":{\"POSITION\":" + std::to_string(p) +
      "},\"indices\":" + std::to_string(fan) +
      ",\"mode\":6},{\"attributes\":{\"POSITION\":" + std::to_string(p) + "},\"mode\":1}]}]";
  const ModelDesc model = parse(a.gltf(body));
  ASSERT_EQ(model.meshes.size(), 2u);
  // glTF 2.0 §3.7.2.1: strip triangle i is (i, i+1+i%2, i+2−i%2).
  EXPECT_EQ(model.meshes[0].indices, (std::vector<uint32_t>{0, 1, 2, 1, 3, 2, 2, 3, 4}));
  EXPECT_EQ(model.meshes[1].indices, (std::vector<uint32_t>{1, 3, 0, 3, 2, 0}));
  ASSERT_EQ(model.warnings.size(), 1u);
  EXPECT_NE(model.warnings[0].find("meshes[0].primitives[2]: points and lines are not rendered"),
            std::string::npos);
}

TEST(GltfLoader, NonIndexedPrimitivesAndU8IndicesRead) {
  GltfAssets a;
  const int p = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}, "VEC3", 3);
  const int u8 = a.accessor(a.view(std::string("\x01\x03\x02", 3)), 5121, 3, "SCALAR");
  const std::string body =
      "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":" +
      std::to_string(p) + "}},{\"attributes\":{\"POSITION\":" + std::to_string(p) +
      "},\"indices\":" + std::to_string(u8) + "}]}]";
  const ModelDesc model = parse(a.gltf(body));
  ASSERT_EQ(model.meshes.size(), 2u);
  EXPECT_EQ(model.meshes[0].indices,
            (std::vector<uint32_t>{0, 1, 2}));  // the 4th vertex: no triangle
  EXPECT_EQ(model.meshes[1].indices, (std::vector<uint32_t>{1, 3, 2}));
  // Primitives without a material get the default one, appended after the file's (none here).
  ASSERT_EQ(model.materials.size(), 1u);
  EXPECT_EQ(model.materials[0].name, "glTF default");
  EXPECT_EQ(model.meshes[0].material, 0u);
  EXPECT_EQ(model.materials[0].diffuse, MaterialDesc{}.diffuse);
}

TEST(GltfLoader, InterleavedStridesNormalizedColoursAndSparsePositionsRead) {
  GltfAssets a;
  // Interleaved position + normal, 24 bytes a vertex.
  const std::vector<float> interleaved = {0, 0, 0, 0, 0, 2, 1, 0, 0, 0, 0, 2, 0, 1, 0, 0, 0, 2};
  const int view = a.view(interleaved, 24);
  const int pos = a.accessor(view, 5126, 3, "VEC3");
  const int nrm = a.accessor(view, 5126, 3, "VEC3", ",\"byteOffset\":12");
  const int rgba8 =
      a.accessor(a.view(std::string("\xff\x00\x33\x80\x00\xff\x00\xff\x00\x00\xff\x10", 12)), 5121,
                 3, "VEC4", ",\"normalized\":true");
  const std::vector<uint16_t> u16 = {65535, 0, 0, 0, 65535, 0, 0, 0, 65535};
  const int rgb16 = a.accessor(a.view(u16), 5123, 3, "VEC3", ",\"normalized\":true");
  // Sparse: vertex 1 of a zero-filled accessor (no buffer view) replaced by (5, 6, 7).
  const int sparseIdx = a.view(std::vector<uint8_t>{1});
  const int sparseVal = a.view(std::vector<float>{5, 6, 7});
  const int sparse = a.accessor(
      -1, 5126, 3, "VEC3",
      ",\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":" + std::to_string(sparseIdx) +
          ",\"componentType\":5121},"
          "\"values\":{\"bufferView\":" +
          std::to_string(sparseVal) + "}}");
  const std::string prim = "{\"attributes\":{\"POSITION\":" + std::to_string(pos) +
                           ",\"NORMAL\":" + std::to_string(nrm) + ",\"COLOR_0\":";
  const std::string body = "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[" + prim +
                           std::to_string(rgba8) + "}}," + prim + std::to_string(rgb16) +
                           "}},{\"attributes\":{\"POSITION\":" + std::to_string(sparse) + "}}]}]";
  const ModelDesc model = parse(a.gltf(body));
  ASSERT_EQ(model.meshes.size(), 3u);
  EXPECT_EQ(model.meshes[0].positions[1], Vec3(1, 0, 0));
  EXPECT_EQ(model.meshes[0].normals[2], Vec3(0, 0, 1));  // normalised
  ASSERT_EQ(model.meshes[0].colors.size(), 3u);
  EXPECT_NEAR(model.meshes[0].colors[0].r, 1.0f, 1e-6f);  // alpha dropped
  EXPECT_NEAR(model.meshes[0].colors[0].g, 0.0f, 1e-6f);
  EXPECT_NEAR(model.meshes[0].colors[0].b, 0.2f, 1e-6f);  // 0x33 / 255
  EXPECT_EQ(model.meshes[1].colors[1], Color(0.0f, 1.0f, 0.0f));
  EXPECT_EQ(model.meshes[2].positions[0], Vec3(0.0f));
  EXPECT_EQ(model.meshes[2].positions[1], Vec3(5, 6, 7));
}

TEST(GltfLoader, NodeTransformsComposeAndMirroredOnesFlipTheWinding) {
  GltfAssets a;
  const int p = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  const int n = a.floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
  const int i = a.indices({0, 1, 2});
  // Parent: a column-major matrix translating by (10, 0, 0). Child: TRS, translate (0, 5, 0),
  // rotate 90° about +Z, scale 2. Second child: scale (-1, 1, 1), a mirror.
  const std::string body =
      "\"scene\":1,\"scenes\":[{\"nodes\":[]},{\"nodes\":[0]}],"
      "\"nodes\":[{\"matrix\":[1,0,0,0, 0,1,0,0, 0,0,1,0, 10,0,0,1],\"children\":[1,2]},"
      "{\"mesh\":0,\"translation\":[0,5,0],\"rotation\":[0,0,0.70710678,0.70710678],\"scale\":[2,2,"
      "2]},"
      "{\"mesh\":0,\"scale\":[-1,1,1]}],"
      "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":" +
      std::to_string(p) + ",\"NORMAL\":" + std::to_string(n) +
      "},\"indices\":" + std::to_string(i) + "}]}]";
  const ModelDesc model = parse(a.gltf(body));
  ASSERT_EQ(model.meshes.size(), 2u);
  const MeshDesc& turned = model.meshes[0];
  // (1, 0, 0) → scaled (2, 0, 0) → rotated (0, 2, 0) → (0, 7, 0) → (10, 7, 0).
  EXPECT_NEAR(turned.positions[1].x, 10.0f, 1e-5f);
  EXPECT_NEAR(turned.positions[1].y, 7.0f, 1e-5f);
  EXPECT_NEAR(turned.positions[2].x, 8.0f, 1e-5f);
  EXPECT_NEAR(turned.positions[2].y, 5.0f, 1e-5f);
  EXPECT_EQ(turned.indices, (std::vector<uint32_t>{0, 1, 2}));
  EXPECT_NEAR(turned.normals[0].z, 1.0f, 1e-6f);
  const MeshDesc& mirrored = model.meshes[1];
  EXPECT_EQ(mirrored.positions[1], Vec3(9, 0, 0));
  EXPECT_EQ(mirrored.indices, (std::vector<uint32_t>{0, 2, 1}));  // still facing its normal
  EXPECT_NEAR(mirrored.normals[0].z, 1.0f, 1e-6f);
}

TEST(GltfLoader, WithoutScenesEveryRootNodeIsPlaced) {
  GltfAssets a;
  const int p = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  const std::string body =
      "\"nodes\":[{\"children\":[1]},{\"mesh\":0},{\"mesh\":0,"
      "\"translation\":[0,0,3]}],\"meshes\":[{\"primitives\":[{\"attributes\":"
      "{\"POSITION\":" +
      std::to_string(p) + "}}]}]";
  const ModelDesc model = parse(a.gltf(body));
  ASSERT_EQ(model.meshes.size(), 2u);
  EXPECT_EQ(model.meshes[1].positions[0], Vec3(0, 0, 3));
}

TEST(GltfLoader, TheFirstCameraAndThePunctualLightsAreRead) {
  GltfAssets a;
  const std::string body = gltftest::oneTriangle(
      a, "\"children\":[1,2,3,4,5]",
      ",\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.5,\"znear\":0.1}},"
      "{\"type\":\"orthographic\",\"orthographic\":{\"xmag\":3,\"ymag\":2,\"znear\":0,\"zfar\":9}}]"
      ","
      "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[{\"type\":\"point\",\"color\":[1,0.5,0]"
      ","
      "\"intensity\":683},{\"type\":\"spot\",\"intensity\":1366},{\"type\":\"directional\"}]}},"
      "\"extensionsUsed\":[\"KHR_lights_punctual\"]");
  std::string withChildren = body;
  withChildren.replace(
      withChildren.find("}],\"meshes\""), 2,
      "},{\"camera\":0,\"translation\":[0,0,5]},{\"camera\":1},"
      "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}},\"translation\":[1,2,3]},"
      "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":1}}},"
      "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":2}}}]");
  const ModelDesc model = parse(a.gltf(withChildren));
  ASSERT_TRUE(model.camera);
  EXPECT_EQ(model.camera->projection, Projection::Perspective);
  EXPECT_EQ(model.camera->position, Vec3(0, 0, 5));
  EXPECT_EQ(model.camera->lookAt, Vec3(0, 0, 4));
  EXPECT_EQ(model.camera->up, Vec3(0, 1, 0));
  EXPECT_NEAR(model.camera->fovDegrees, 0.5f * 180.0f / 3.14159265f, 1e-4f);
  ASSERT_EQ(model.lights.size(), 2u);  // the directional light is skipped
  EXPECT_EQ(model.lights[0].position, Vec3(1, 2, 3));
  EXPECT_EQ(model.lights[0].intensity, Color(1.0f, 0.5f, 0.0f));  // 683 cd = 1 W/sr
  EXPECT_EQ(model.lights[1].intensity, Color(2.0f));
  std::string warnings;
  for (const std::string& w : model.warnings) warnings += w + "\n";
  EXPECT_NE(warnings.find("a further camera is skipped"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("a spot light's cone is not modelled"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("directional lights are not modelled"), std::string::npos) << warnings;
}

TEST(GltfLoader, AnOrthographicCameraTakesItsWidthFromXmag) {
  GltfAssets a;
  const ModelDesc model = parse(a.gltf(
      gltftest::oneTriangle(a, "\"camera\":0",
                            ",\"cameras\":[{\"type\":\"orthographic\",\"orthographic\":{\"xmag\":3,"
                            "\"ymag\":2,\"znear\":0,\"zfar\":9}}]")));
  ASSERT_TRUE(model.camera);
  EXPECT_EQ(model.camera->projection, Projection::Orthographic);
  EXPECT_EQ(model.camera->width, 6.0f);
}

TEST(GltfLoader, UnknownExtensionsUsedAreNamedInOneWarning) {
  GltfAssets a;
  const ModelDesc model = parse(a.gltf(gltftest::oneTriangle(
      a, "",
      ",\"extensionsUsed\":[\"KHR_texture_transform\",\"EXT_foo\",\"KHR_materials_sheen\"]")));
  ASSERT_EQ(model.warnings.size(), 1u);
  EXPECT_EQ(model.warnings[0],
            "model.gltf: extensionsUsed: EXT_foo, KHR_materials_sheen not read: "
            "what they add is ignored, the rest of the file is used");
}

TEST(GltfLoader, AModelLargerThanTheMemoryLimitIsRefusedBeforeItIsRead) {
  GltfAssets a;
  const std::string gltf = a.gltf(gltftest::oneTriangle(a));
  EXPECT_NO_THROW(parse(gltf, "model.gltf", {}, MemoryLimit{1 << 20, "test"}));
  try {
    parse(gltf, "model.gltf", {}, MemoryLimit{2000, "test"});
    ADD_FAILURE() << "accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("the memory limit is"), std::string::npos) << e.what();
  }
  // 4·10^9 zero vertices (no buffer view holds them, so no bounds check stops them): refused
  // from the count alone, before anything is allocated; more than 2^32 in one primitive cannot
  // be indexed at all.
  for (const uint64_t count : {4000000000ull, 1000000000000ull}) {
    GltfAssets huge;
    const int p = huge.accessor(-1, 5126, count, "VEC3");
    huge.view(std::vector<float>{0});
    const std::string body =
        "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":"
        "{\"POSITION\":" +
        std::to_string(p) + "}}]}]";
    try {
      parse(huge.gltf(body), "model.gltf", {}, MemoryLimit{1ull << 34, "test"});
      ADD_FAILURE() << "accepted";
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(count == 4000000000ull
                                               ? "(1333333333 triangles, 4000000000 vertices) read "
                                                 "and built needs"
                                               : "more than 2^32 vertices in one primitive"),
                std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace prism
