// Models placed into scenes (placeModel) and rendered as scenes of their own (sceneOfModel).
#include "parse/ModelFile.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "parse/ModelScene.h"
#include "parse/SceneLoader.h"
#include "scene/Camera.h"

namespace prism {
namespace {

namespace fs = std::filesystem;

TextureDesc namedTexture(const std::string& path, uint8_t value) {
  TextureDesc t;
  t.path = path;
  t.srgb = SrgbImage{1, 1, {value, value, value}};
  return t;
}

// Two materials (the second textured by texture 1), two textures, one mesh of three faces.
ModelDesc twoMaterialModel() {
  ModelDesc model;
  model.source = "model.obj";
  MeshDesc mesh;
  mesh.source = "model.obj";
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}};
  mesh.indices = {0, 1, 2, 0, 2, 3, 0, 3, 4};
  mesh.faceMaterials = {1, 0, 1};
  model.meshes = {mesh};
  MaterialDesc plain, textured;
  plain.name = "plain";
  textured.name = "textured";
  textured.diffuseMap = TextureMap{1};
  model.materials = {plain, textured};
  model.textures = {namedTexture("a.png", 10), namedTexture("b.png", 20)};
  model.warnings = {"model.mtl:4: 'map_Bump' is not modelled: skipped"};
  return model;
}

TEST(ModelFile, PlacingAModelRenumbersItsMaterialsAndTexturesIntoTheScenes) {
  SceneDescription scene;
  scene.materials.resize(3);                     // the scene's own come first
  scene.textures = {namedTexture("b.png", 20)};  // another model's, the same file
  const size_t first = placeModel(twoMaterialModel(), ModelPlacement{}, scene);
  EXPECT_EQ(first, 0u);
  ASSERT_EQ(scene.materials.size(), 5u);
  EXPECT_EQ(scene.materials[4].name, "textured");
  ASSERT_EQ(scene.textures.size(), 2u);  // b.png held once
  EXPECT_EQ(scene.textures[1].path, "a.png");
  EXPECT_EQ(scene.materials[4].diffuseMap->texture, 0u);  // b.png, the scene's texture 0
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.meshes[0].faceMaterials, (std::vector<MaterialId>{4, 3, 4}));
  EXPECT_EQ(scene.meshes[0].material, 3u);
  EXPECT_EQ(scene.warnings, twoMaterialModel().warnings);
}

TEST(ModelFile, ASceneMaterialOverridesEveryFace) {
  SceneDescription scene;
  scene.materials.resize(2);
  ModelPlacement placement;
  placement.material = 1;
  placement.caustic = CausticRole::Cast;
  placeModel(twoMaterialModel(), placement, scene);
  EXPECT_EQ(scene.materials.size(), 2u);  // the model's are not added
  EXPECT_TRUE(scene.textures.empty());
  EXPECT_TRUE(scene.meshes[0].faceMaterials.empty());
  EXPECT_EQ(scene.meshes[0].material, 1u);
  EXPECT_EQ(scene.meshes[0].caustic, CausticRole::Cast);
}

class ModelSceneFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("prism_model_scene_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    const fs::path path = dir_ / name;
    std::ofstream(path) << text;
    return path.string();
  }
  fs::path dir_;
};

// A box from (-2, 0, -1) to (4, 3, 1): off the origin and longer in x.
constexpr const char* kBoxObj =
    "v -2 0 -1\nv 4 0 -1\nv 4 3 -1\nv -2 3 -1\nv -2 0 1\nv 4 0 1\nv 4 3 1\nv -2 3 1\n"
    "f 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 4 3 7 8\nf 1 4 8 5\nf 2 6 7 3\n";

TEST_F(ModelSceneFiles, AModelWithoutCameraOrLightsIsFramedAndLit) {
  const SceneDescription scene = loadScene(write("box.obj", kBoxObj));
  ASSERT_EQ(scene.meshes.size(), 1u);
  ASSERT_EQ(scene.lights.size(), 1u);
  ASSERT_EQ(scene.notes.size(), 2u);
  EXPECT_EQ(scene.notes[0], "camera: none in the file, so one framing the model's bounds");
  EXPECT_EQ(scene.notes[1], "lights: none in the file, so one above the camera");
  // Every corner of the box is in the picture, and the camera looks at the box's centre.
  const Camera camera(scene.camera, scene.render.width, scene.render.height);
  EXPECT_EQ(scene.camera.lookAt, Vec3(1.0f, 1.5f, 0.0f));
  for (const Vec3& corner : scene.meshes[0].positions) {
    const std::optional<Vec2> p = camera.project(corner);
    ASSERT_TRUE(p.has_value());
    EXPECT_GT(p->x, 0.0f);
    EXPECT_LT(p->x, static_cast<float>(scene.render.width));
    EXPECT_GT(p->y, 0.0f);
    EXPECT_LT(p->y, static_cast<float>(scene.render.height));
  }
  // The light shows the shape: it lies on the camera's side, above it, off its axis.
  EXPECT_GT(scene.lights[0].position.y, scene.camera.position.y);
  EXPECT_GT(glm::dot(scene.lights[0].position - scene.camera.lookAt,
                     scene.camera.position - scene.camera.lookAt),
            0.0f);
}

TEST(ModelScene, AModelsOwnCameraAndLightsAreKept) {
  ModelDesc model = twoMaterialModel();
  CameraDesc camera;
  camera.position = Vec3(7, 8, 9);
  camera.fovDegrees = 30.0f;
  model.camera = camera;
  PointLightDesc light;
  light.position = Vec3(1, 2, 3);
  model.lights = {light, light};
  const SceneDescription scene = sceneOfModel(model);
  EXPECT_EQ(scene.camera.position, Vec3(7, 8, 9));
  EXPECT_EQ(scene.camera.fovDegrees, 30.0f);
  EXPECT_EQ(scene.lights.size(), 2u);
  EXPECT_EQ(scene.notes[0], "camera: the file's own");
  EXPECT_EQ(scene.notes[1], "lights: the file's own (2)");
  EXPECT_EQ(scene.materials.size(), 2u);
  EXPECT_EQ(scene.textures.size(), 2u);
}

}  // namespace
}  // namespace prism
