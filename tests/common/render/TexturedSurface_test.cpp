// Textured surfaces as the renderer shows them: the texel under a pixel, and a fine texture
// receding to the horizon filtered by the rays' cones as supersampling would average it.
#include <gtest/gtest.h>

#include <cmath>

#include "image/SrgbImage.h"
#include "render/TileRenderer.h"
#include "render/WhittedIntegrator.h"
#include "scene/Scene.h"

namespace prism {
namespace {

// A quad of two triangles with texture coordinates at its corners (counter-clockwise from
// corner a).
MeshDesc texturedQuad(Vec3 a, Vec3 b, Vec3 c, Vec3 d, Vec2 ta, Vec2 tb, Vec2 tc, Vec2 td) {
  MeshDesc mesh;
  mesh.source = "quad";
  mesh.positions = {a, b, c, d};
  mesh.uvs = {ta, tb, tc, td};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  return mesh;
}

TextureDesc checkerTexture(int size, int cell, uint8_t dark, uint8_t light) {
  TextureDesc t;
  t.path = "checker.png";
  t.srgb.width = t.srgb.height = size;
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const uint8_t v = ((x / cell + y / cell) & 1) ? light : dark;
      t.srgb.rgb.insert(t.srgb.rgb.end(), {v, v, v});
    }
  }
  return t;
}

// A white Lambertian material that reads texture 0.
MaterialDesc texturedWhite() {
  MaterialDesc m;
  m.name = "textured";
  m.diffuse = Color(1.0f);
  m.specular = Color(0.0f);
  m.diffuseMap = TextureMap{};
  return m;
}

TEST(TexturedSurface, TheTexelAtAFacesCentreIsWhatThePixelShows) {
  // A 9×9 texture whose middle 3×3 texels are another colour; the quad faces the camera and a
  // light at the camera of intensity π·d², so the radiance is the albedo itself.
  TextureDesc texture;
  texture.path = "marked.png";
  texture.srgb.width = texture.srgb.height = 9;
  for (int y = 0; y < 9; ++y) {
    for (int x = 0; x < 9; ++x) {
      const bool middle = x >= 3 && x < 6 && y >= 3 && y < 6;
      const uint8_t r = middle ? 180 : 40, g = middle ? 90 : 200, b = middle ? 20 : 100;
      texture.srgb.rgb.insert(texture.srgb.rgb.end(), {r, g, b});
    }
  }
  SceneDescription d;
  d.render.width = d.render.height = 33;
  d.camera.position = Vec3(0, 0, 5);
  d.materials = {texturedWhite()};
  d.textures = {texture};
  d.meshes = {
      texturedQuad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {0, 0}, {1, 0}, {1, 1}, {0, 1})};
  PointLightDesc light;
  light.position = d.camera.position;
  light.intensity = Color(kPi * 25.0f);
  d.lights = {light};
  const Scene scene(d);
  const TileRenderer renderer(scene);
  const TileResult tile = renderer.render(0, TileRect{16, 16, 1, 1});
  const auto& linear = linearOfSrgbByte();
  const Color expected(linear[180], linear[90], linear[20]);
  EXPECT_NEAR(tile.pixels[0].x, expected.x, 1e-5f * 1.0f + 1e-4f * expected.x);
  EXPECT_NEAR(tile.pixels[0].y, expected.y, 1e-5f * 1.0f + 1e-4f * expected.y);
  EXPECT_NEAR(tile.pixels[0].z, expected.z, 1e-5f * 1.0f + 1e-4f * expected.z);
}

// A floor of a fine checker (cells of a quarter unit) receding to the horizon, lit from high
// above.
SceneDescription recedingChecker(int samples) {
  SceneDescription d;
  d.render.width = 96;
  d.render.height = 54;
  d.render.samplesPerPixel = samples;
  d.camera.position = Vec3(0.0f, 1.0f, 5.0f);
  d.camera.lookAt = Vec3(0.0f, 0.55f, -10.0f);
  d.materials = {texturedWhite()};
  d.textures = {checkerTexture(8, 2, 30, 230)};
  d.materials[0].diffuseMap->scale = Vec2(0.5f);  // the 8-texel texture spans 2 units
  const float x = 400.0f, far = -800.0f, nearZ = 6.0f;
  d.meshes = {texturedQuad({-x, 0, nearZ}, {x, 0, nearZ}, {x, 0, far}, {-x, 0, far}, {-x, -nearZ},
                           {x, -nearZ}, {x, -far}, {-x, -far})};
  PointLightDesc light;
  light.position = Vec3(0.0f, 2000.0f, -200.0f);
  light.intensity = Color(kPi * 2000.0f * 2000.0f);
  d.lights = {light};
  return d;
}

double rmse(const std::vector<Color>& a, const std::vector<Color>& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    const Color e = a[i] - b[i];
    sum += glm::dot(e, e) / 3.0;
  }
  return std::sqrt(sum / static_cast<double>(a.size()));
}

TEST(TexturedSurface, AFineTextureToTheHorizonIsFilteredLikeSupersamplingWithoutMoire) {
  const SceneDescription one = recedingChecker(1), many = recedingChecker(64);
  const TileRect whole{0, 0, one.render.width, one.render.height};
  const Scene scene(one), reference(many);
  const std::vector<Color> filtered = TileRenderer(scene).render(0, whole).pixels;
  const std::vector<Color> supersampled = TileRenderer(reference).render(0, whole).pixels;
  // The same pixels' centres read at the texture's finest level: what no filter gives.
  const WhittedIntegrator integrator(scene);
  std::vector<Color> point;
  RayCounters rays;
  for (int y = 0; y < whole.height; ++y) {
    for (int x = 0; x < whole.width; ++x) {
      const Ray ray = scene.camera().generateRay(x + 0.5f, y + 0.5f);
      point.push_back(integrator.radiance(ray, 0, Color(1.0f), rays));
    }
  }
  const double filteredError = rmse(filtered, supersampled), pointError = rmse(point, supersampled);
  RecordProperty("filtered_rmse", std::to_string(filteredError));
  RecordProperty("point_rmse", std::to_string(pointError));
  // Stated in docs/accuracy.md ("Textures"): the cones' 1-spp image within 0.06 of the 64-spp
  // one, where point sampling aliases to several times that.
  EXPECT_LT(filteredError, 0.06) << "point sampling: " << pointError;
  EXPECT_LT(filteredError, 0.4 * pointError);
}

TEST(TexturedSurface, PacketsAndSingleRaysReadTexturesAlike) {
  SceneDescription d = recedingChecker(3);
  const Scene scene(d);
  TileRenderer packets(scene), single(scene);
  single.setCameraRays(CameraRays::OneByOne);
  const TileRect rect{3, 5, 41, 29};
  const std::vector<Color> a = packets.render(0, rect).pixels, b = single.render(0, rect).pixels;
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], b[i]) << i;
}

}  // namespace
}  // namespace prism
