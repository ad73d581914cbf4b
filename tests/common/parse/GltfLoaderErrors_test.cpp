// Bad glTF input, one class at a time: each is refused with "file: where: what is wrong" and no
// model (docs/scene-format.md, "glTF", lists them).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/parse/GltfAssets.h"
#include "parse/GltfLoader.h"

namespace prism {
namespace {

using gltftest::GltfAssets;

std::string errorOf(const std::string& bytes, const std::string& name = "model.gltf",
                    const std::map<std::string, std::string>& files = {}) {
  try {
    gltftest::parse(bytes, name, files);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "accepted";
}

std::string mesh(int position, const std::string& more = "") {
  return "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":" +
         std::to_string(position) + "}" + more + "}]}]";
}

TEST(GltfLoaderErrors, IndicesOutOfRange) {
  GltfAssets a;
  const int p = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  const int i = a.indices({0, 1, 7});
  EXPECT_EQ(errorOf(a.gltf(mesh(p, ",\"indices\":" + std::to_string(i)))),
            "model.gltf: accessors[1]: index 7 is out of range (meshes[0].primitives[0] has 3 "
            "vertices)");
}

TEST(GltfLoaderErrors, AccessorsPastTheirBufferViewAndViewsPastTheirBuffer) {
  GltfAssets a;
  const int view = a.view(std::vector<float>(9, 0.0f));
  const int p = a.accessor(view, 5126, 4, "VEC3");
  EXPECT_EQ(errorOf(a.gltf(mesh(p))),
            "model.gltf: accessors[0]: 4 elements from byte 0 need 48 bytes, but the buffer view "
            "has 36");
  GltfAssets b;
  b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  b.views[0] = "{\"buffer\":0,\"byteOffset\":8,\"byteLength\":36}";
  EXPECT_EQ(errorOf(b.gltf(mesh(0))),
            "model.gltf: bufferViews[0]: bytes 8 to 44 lie past the end of buffers[0] (36 bytes)");
  GltfAssets c;
  c.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  std::string json = c.gltf(mesh(0));
  json.replace(json.find("\"byteLength\":36}]"), 16, "\"byteLength\":40}");
  EXPECT_EQ(errorOf(json),
            "model.gltf: buffers[0].byteLength: 40 bytes, but its data URI holds 36");
  EXPECT_EQ(errorOf(c.gltf(mesh(3))),
            "model.gltf: meshes[0].primitives[0].attributes.POSITION: refers to accessors[3], but "
            "the file has 1");
}

TEST(GltfLoaderErrors, AMissingBinAndABadDataUri) {
  GltfAssets a;
  a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  EXPECT_EQ(errorOf(a.json(mesh(0), "mesh.bin")),
            "model.gltf: buffers[0].uri: the buffer file 'mesh.bin' is missing");
  EXPECT_EQ(errorOf(a.json(mesh(0), "mesh.bin"), "model.gltf", {{"mesh.bin", a.bin}}), "accepted");
  EXPECT_EQ(errorOf(a.json(mesh(0), "data:application/octet-stream;base64,AA!A")),
            "model.gltf: buffers[0].uri: '!' at character 2 is not base64");
}

TEST(GltfLoaderErrors, WrongJsonTypesAndInvalidJson) {
  GltfAssets a;
  a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  std::string json = a.gltf(mesh(0));
  json.replace(json.find("{\"mesh\":0}"), 10, "{\"mesh\":\"zero\"}");
  EXPECT_EQ(errorOf(json),
            "model.gltf: nodes[0].mesh: expected an integer of 0 or more, found a string");
  EXPECT_EQ(errorOf("{\"asset\":{\"version\":\"2.0\"},\"nodes\":{}}"),
            "model.gltf: nodes: expected an array, found an object");
  EXPECT_NE(errorOf("{\"asset\": [").find("model.gltf: not valid JSON: "), std::string::npos);
  EXPECT_EQ(errorOf("[1]"), "model.gltf: not a glTF file: the JSON is not an object");
  EXPECT_EQ(errorOf("{\"asset\":{\"version\":\"1.0\"}}"),
            "model.gltf: asset.version: glTF 1.0 is not read (only glTF 2.0; convert older files, "
            "e.g. with Blender)");
  EXPECT_EQ(errorOf("{}"), "model.gltf: 'asset' is missing");
}

TEST(GltfLoaderErrors, CyclesAndSharedNodes) {
  GltfAssets a;
  a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  const std::string meshes = ",\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}]";
  EXPECT_EQ(errorOf(a.gltf("\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"children\":[1]},"
                           "{\"children\":[0],\"mesh\":0}]" +
                           meshes)),
            "model.gltf: nodes[1].children[0]: nodes[0] is reached twice: the node graph has a "
            "cycle or lists a node twice");
  EXPECT_EQ(errorOf(a.gltf("\"nodes\":[{\"children\":[0],\"mesh\":0}]" + meshes)),
            "model.gltf: nodes[0].children[0]: nodes[0] lists itself as a child (a cycle)");
  EXPECT_EQ(
      errorOf(a.gltf("\"nodes\":[{\"children\":[2]},{\"children\":[2]},{\"mesh\":0}]" + meshes)),
      "model.gltf: nodes[1].children[0]: nodes[2] is already a child of nodes[0] (glTF nodes "
      "form trees, without shared nodes)");
}

TEST(GltfLoaderErrors, NonFinitePositions) {
  GltfAssets a;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const int p = a.floats({0, 0, 0, 1, nan, 0, 0, 1, 0}, "VEC3", 3);
  EXPECT_EQ(errorOf(a.gltf(mesh(p))),
            "model.gltf: accessors[0]: position 1 is not finite (as read, or once the node's "
            "transform is applied)");
  GltfAssets b;
  b.floats({0, 0, 0, 1e30f, 0, 0, 0, 1, 0}, "VEC3", 3);
  EXPECT_NE(
      errorOf(b.gltf("\"nodes\":[{\"mesh\":0,\"scale\":[1e30,1,1]}],\"meshes\":[{\"primitives\":"
                     "[{\"attributes\":{\"POSITION\":0}}]}]"))
          .find("position 1 is not finite"),
      std::string::npos);
}

TEST(GltfLoaderErrors, TruncatedAndForeignGlbFiles) {
  GltfAssets a;
  a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  const std::string glb = a.glb(mesh(0));
  EXPECT_EQ(errorOf(glb, "model.glb"), "accepted");
  EXPECT_NE(errorOf(glb.substr(0, glb.size() - 10), "model.glb")
                .find("model.glb: byte 8: the header says the file has"),
            std::string::npos);
  EXPECT_EQ(errorOf("{\"asset\":{\"version\":\"2.0\"}}", "model.glb"),
            "model.glb: byte 0: not a binary glTF file (no \"glTF\" magic)");
}

TEST(GltfLoaderErrors, TexturesThatAreNotImages) {
  GltfAssets a;
  const int p = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  const std::string body =
      mesh(p, ",\"material\":0") +
      ",\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}],"
      "\"textures\":[{\"source\":0}],\"images\":[{\"uri\":\"data:image/png;base64," +
      gltftest::base64("hello, not a PNG") + "\"}]";
  EXPECT_EQ(errorOf(a.gltf(body)),
            "model.gltf: images[0]: texture 'model.gltf#images[0]': not a PNG or JPEG image");
}

TEST(GltfLoaderErrors, RequiredExtensionsPrismCannotReadAreRefusedByName) {
  GltfAssets a;
  const std::string body = gltftest::oneTriangle(
      a, "",
      ",\"extensionsUsed\":[\"KHR_draco_mesh_compression\"],\"extensionsRequired\":"
      "[\"KHR_draco_mesh_compression\"]");
  EXPECT_EQ(errorOf(a.gltf(body)),
            "model.gltf: extensionsRequired[0]: the file requires KHR_draco_mesh_compression, "
            "which Prism cannot read (supported: KHR_texture_transform, "
            "KHR_materials_transmission, KHR_materials_ior, KHR_lights_punctual, "
            "KHR_mesh_quantization)");
  GltfAssets b;
  EXPECT_EQ(errorOf(b.gltf(gltftest::oneTriangle(
                b, "", ",\"extensionsRequired\":[\"KHR_texture_transform\"]"))),
            "accepted");
}

TEST(GltfLoaderErrors, AttributeCountsDisagree) {
  GltfAssets a;
  const int p = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  const int n = a.floats({0, 0, 1, 0, 0, 1}, "VEC3", 3);
  std::string body = mesh(p);
  body.replace(body.find("}}]}]"), 1, ",\"NORMAL\":" + std::to_string(n) + "}");
  EXPECT_EQ(errorOf(a.gltf(body)),
            "model.gltf: meshes[0].primitives[0].attributes.NORMAL: NORMAL has 2 elements, "
            "POSITION has 3");
}

TEST(GltfLoaderErrors, ASceneWithOnlyPointsIsRefused) {
  GltfAssets a;
  const int p = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  EXPECT_EQ(errorOf(a.gltf(mesh(p, ",\"mode\":0"))),
            "model.gltf: the default scene has no triangles (only points and lines, which Prism "
            "does not render)");
}

}  // namespace
}  // namespace prism
