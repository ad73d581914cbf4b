#include "wire/SceneCodec.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>

#include "parse/SceneLoader.h"
#include "wire/Messages.h"

namespace prism::wire {
namespace {

// Every field away from its default, so a field the codec forgets cannot pass by luck.
SceneDescription fullScene() {
  SceneDescription d;
  d.sourcePath = "scenes/everything.yaml";
  d.camera = {
      Projection::Orthographic, {1, 2, 3}, {-1, 0.5f, -0.0f}, {0, 0, 1}, 60.5f, 4.5f, 0.125f,
      {"everything.yaml", 2, 3}};
  d.render = {321,
              203,
              16,
              7,
              0.01f,
              12345678901234ull,
              2.5f,
              TriangleTest::PlaneThenInside,
              InstructionSet::V3};
  d.caustics = {CausticMethod::PhotonMap,
                0x1'0000'0007ull,
                37,
                true,
                0.0375f,
                0.0625f,
                PhotonFilter::Epanechnikov,
                9,
                true,
                33,
                0.55f,
                1e-40f,
                12.5,
                1536,
                7,
                2.25f,
                5,
                CausticMapPaths::FrontFace};
  d.background = {0.1f, 0.2f, 0.3f};
  d.ambientLight = {0.05f, 0.06f, 1e-40f};

  CubeMapDesc cube;
  for (int i = 0; i < 6; ++i) {
    cube.faces[i] = ImageRgb(i % 2 + 1, i % 2 + 1);
    for (size_t p = 0; p < cube.faces[i].pixels.size(); ++p) {
      cube.faces[i].pixels[p] = Color(i, p, 0.5f * i + 0.25f * p);
    }
    cube.paths[i] = "sky/face" + std::to_string(i) + ".exr";
  }
  cube.scale = 3.5f;
  d.environment = cube;

  MaterialDesc floor{"floor",
                     {1, 1, 1},
                     {0.7f, 0.6f, 0.5f},
                     {0.2f, 0.2f, 0.2f},
                     64.0f,
                     {0.1f, 0.2f, 0.3f},
                     {0.0f, 0.1f, 0.0f},
                     1.0f,
                     false,
                     CheckerDesc{{0.9f, 0.8f, 0.7f}, {0.1f, 0.2f, 0.3f}, 0.5f},
                     TextureMap{1, {2.0f, -3.0f}, {0.5f, 0.25f}, 0.75f},
                     {"everything.yaml", 10, 5}};
  MaterialDesc glass{
      "glass", {0.01f, 0, 0},         {0, 0, 0},          {1, 1, 1},
      128.0f,  {0.05f, 0.05f, 0.05f}, {0.9f, 0.9f, 0.9f}, 1.5f,
      true,    std::nullopt,          std::nullopt,       {"everything.yaml", 20, 5}};
  d.materials = {floor, glass};
  TextureDesc bytes;
  bytes.path = "textures/wood.jpg";
  bytes.srgb = SrgbImage{2, 1, {1, 2, 3, 250, 251, 252}};
  TextureDesc floats;
  floats.path = "textures/sky.exr";
  floats.linear = ImageRgb(1, 2);
  floats.linear.pixels = {Color(4.5f, 0.25f, 1e-40f), Color(0.0f, -0.0f, 7.0f)};
  d.textures = {bytes, floats};

  d.lights = {{{0, 5, 0}, {100, 90, 80}, {1, 0.5f, 0.25f}, {"everything.yaml", 30, 5}},
              {{-3, 4, 2}, {1, 2, 3}, {0, 0, 2}, {"everything.yaml", 31, 5}}};
  d.spheres = {{{0, 1, 0}, 0.75f, 1, {"everything.yaml", 40, 5}, CausticRole::Cast},
               {{2, 1, -1}, 0.25f, 0, {"", 0, 0}, CausticRole::Off}};
  d.planes = {{{0, -0.5f, 0}, {0, 1, 0.25f}, 1, {"everything.yaml", 41, 5}, CausticRole::Receive}};
  d.cones = {
      {{2, 0, 0}, 1.0f, {2, 2, 0}, 0.5f, 1, {"everything.yaml", 42, 5}, CausticRole::Both},
      {{-2, 0, 0}, 0.25f, {-2, 3, 0}, 0.25f, 0, {"everything.yaml", 43, 5}, CausticRole::Off}};
  d.discs = {{{0, 2, 1}, {0.6f, 0.8f, 0}, 0.5f, 1, {"everything.yaml", 45, 5}, CausticRole::Cast}};

  MeshDesc smooth;
  smooth.source = "meshes/quad.obj";
  smooth.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  smooth.normals = {{0, 0, 1}, {0, 0.1f, 1}, {0.1f, 0, 1}, {0, 0, -1}};
  smooth.indices = {0, 1, 2, 0, 2, 3};
  smooth.material = 1;
  smooth.loc = {"everything.yaml", 44, 5};
  smooth.caustic = CausticRole::Both;
  smooth.uvs = {{0, 0}, {1, 0}, {1, 1.5f}, {-0.25f, 1}};
  smooth.colors = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.5f, 0.5f, 1e-40f}};
  smooth.faceMaterials = {1, 0};
  MeshDesc flat;
  flat.source = "triangle";
  flat.positions = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
  flat.indices = {2, 1, 0};
  flat.material = 0;
  flat.loc = {"everything.yaml", 50, 7};
  flat.caustic = CausticRole::Receive;
  d.meshes = {smooth, flat};
  d.warnings = {"meshes/quad.mtl:3: 'map_Bump' is not modelled: skipped"};
  d.notes = {"camera: the file's own"};
  return d;
}

SceneDescription roundTrip(const SceneDescription& d) {
  return decodeScene(decodeMessage(encodeScene(d)));
}

SceneDescription decodeBytes(const std::vector<uint8_t>& payload) {
  ByteReader r(payload);
  SceneDescription d = readScene(r);
  r.expectEnd();
  return d;
}

std::vector<uint8_t> payloadOf(const SceneDescription& d) {
  ByteWriter w;
  writeScene(w, d);
  return w.take();
}

void expectWireError(const SceneDescription& d, const std::string& fragment) {
  const std::vector<uint8_t> bytes = payloadOf(d);
  try {
    decodeBytes(bytes);
    ADD_FAILURE() << "no WireError; expected one containing \"" << fragment << "\"";
  } catch (const WireError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

// Floats compare by bit pattern: -0, denormals and NaNs must arrive exactly as sent.
#define EXPECT_SAME_FLOAT(a, b) EXPECT_EQ(std::bit_cast<uint32_t>(a), std::bit_cast<uint32_t>(b))
#define EXPECT_SAME_VEC3(a, b)       \
  do {                               \
    EXPECT_SAME_FLOAT((a).x, (b).x); \
    EXPECT_SAME_FLOAT((a).y, (b).y); \
    EXPECT_SAME_FLOAT((a).z, (b).z); \
  } while (false)

void expectSameLoc(const FileLoc& a, const FileLoc& b) {
  EXPECT_EQ(a.file, b.file);
  EXPECT_EQ(a.line, b.line);
  EXPECT_EQ(a.column, b.column);
}

void expectSameVec3s(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) EXPECT_SAME_VEC3(a[i], b[i]);
}

void expectSameImage(const ImageRgb& a, const ImageRgb& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  expectSameVec3s(a.pixels, b.pixels);
}

void expectSameScene(const SceneDescription& a, const SceneDescription& b) {
  EXPECT_EQ(a.sourcePath, b.sourcePath);

  EXPECT_EQ(a.camera.projection, b.camera.projection);
  EXPECT_SAME_VEC3(a.camera.position, b.camera.position);
  EXPECT_SAME_VEC3(a.camera.lookAt, b.camera.lookAt);
  EXPECT_SAME_VEC3(a.camera.up, b.camera.up);
  EXPECT_SAME_FLOAT(a.camera.fovDegrees, b.camera.fovDegrees);
  EXPECT_SAME_FLOAT(a.camera.width, b.camera.width);
  EXPECT_SAME_FLOAT(a.camera.nearClip, b.camera.nearClip);
  expectSameLoc(a.camera.loc, b.camera.loc);

  EXPECT_EQ(a.render.width, b.render.width);
  EXPECT_EQ(a.render.height, b.render.height);
  EXPECT_EQ(a.render.samplesPerPixel, b.render.samplesPerPixel);
  EXPECT_EQ(a.render.maxDepth, b.render.maxDepth);
  EXPECT_SAME_FLOAT(a.render.minContribution, b.render.minContribution);
  EXPECT_EQ(a.render.seed, b.render.seed);
  EXPECT_SAME_FLOAT(a.render.exposure, b.render.exposure);
  EXPECT_EQ(a.render.triangleTest, b.render.triangleTest);
  EXPECT_EQ(a.render.instructionSet, b.render.instructionSet);

  EXPECT_EQ(a.caustics.method, b.caustics.method);
  EXPECT_EQ(a.caustics.photons, b.caustics.photons);
  EXPECT_EQ(a.caustics.gather, b.caustics.gather);
  EXPECT_SAME_FLOAT(a.caustics.maxRadius, b.caustics.maxRadius);
  EXPECT_EQ(a.caustics.filter, b.caustics.filter);
  EXPECT_EQ(a.caustics.maxBounces, b.caustics.maxBounces);
  EXPECT_EQ(a.caustics.progressive, b.caustics.progressive);
  EXPECT_EQ(a.caustics.passes, b.caustics.passes);
  EXPECT_SAME_FLOAT(a.caustics.alpha, b.caustics.alpha);
  EXPECT_SAME_FLOAT(a.caustics.radius, b.caustics.radius);
  EXPECT_EQ(std::bit_cast<uint64_t>(a.caustics.timeBudgetSeconds),
            std::bit_cast<uint64_t>(b.caustics.timeBudgetSeconds));
  EXPECT_EQ(a.caustics.mapResolution, b.caustics.mapResolution);
  EXPECT_EQ(a.caustics.mapSteps, b.caustics.mapSteps);
  EXPECT_SAME_FLOAT(a.caustics.mapBlurSigma, b.caustics.mapBlurSigma);
  EXPECT_EQ(a.caustics.mapBlurRadius, b.caustics.mapBlurRadius);
  EXPECT_EQ(a.caustics.mapPaths, b.caustics.mapPaths);

  EXPECT_SAME_VEC3(a.background, b.background);
  EXPECT_SAME_VEC3(a.ambientLight, b.ambientLight);

  ASSERT_EQ(a.environment.has_value(), b.environment.has_value());
  if (a.environment) {
    for (int i = 0; i < 6; ++i) {
      expectSameImage(a.environment->faces[i], b.environment->faces[i]);
      EXPECT_EQ(a.environment->srgbFaces[i].width, b.environment->srgbFaces[i].width);
      EXPECT_EQ(a.environment->srgbFaces[i].height, b.environment->srgbFaces[i].height);
      EXPECT_EQ(a.environment->srgbFaces[i].rgb, b.environment->srgbFaces[i].rgb);
      EXPECT_EQ(a.environment->paths[i], b.environment->paths[i]);
    }
    EXPECT_SAME_FLOAT(a.environment->scale, b.environment->scale);
  }

  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (size_t i = 0; i < a.materials.size(); ++i) {
    const MaterialDesc& x = a.materials[i];
    const MaterialDesc& y = b.materials[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_SAME_VEC3(x.ambient, y.ambient);
    EXPECT_SAME_VEC3(x.diffuse, y.diffuse);
    EXPECT_SAME_VEC3(x.specular, y.specular);
    EXPECT_SAME_FLOAT(x.shininess, y.shininess);
    EXPECT_SAME_VEC3(x.reflectance, y.reflectance);
    EXPECT_SAME_VEC3(x.transmittance, y.transmittance);
    EXPECT_SAME_FLOAT(x.ior, y.ior);
    EXPECT_EQ(x.fresnel, y.fresnel);
    ASSERT_EQ(x.checker.has_value(), y.checker.has_value());
    if (x.checker) {
      EXPECT_SAME_VEC3(x.checker->colorA, y.checker->colorA);
      EXPECT_SAME_VEC3(x.checker->colorB, y.checker->colorB);
      EXPECT_SAME_FLOAT(x.checker->scale, y.checker->scale);
    }
    ASSERT_EQ(x.diffuseMap.has_value(), y.diffuseMap.has_value());
    if (x.diffuseMap) {
      EXPECT_EQ(x.diffuseMap->texture, y.diffuseMap->texture);
      EXPECT_SAME_FLOAT(x.diffuseMap->scale.x, y.diffuseMap->scale.x);
      EXPECT_SAME_FLOAT(x.diffuseMap->scale.y, y.diffuseMap->scale.y);
      EXPECT_SAME_FLOAT(x.diffuseMap->offset.x, y.diffuseMap->offset.x);
      EXPECT_SAME_FLOAT(x.diffuseMap->offset.y, y.diffuseMap->offset.y);
      EXPECT_SAME_FLOAT(x.diffuseMap->rotation, y.diffuseMap->rotation);
    }
    expectSameLoc(x.loc, y.loc);
  }

  ASSERT_EQ(a.textures.size(), b.textures.size());
  for (size_t i = 0; i < a.textures.size(); ++i) {
    EXPECT_EQ(a.textures[i].path, b.textures[i].path);
    EXPECT_EQ(a.textures[i].srgb.width, b.textures[i].srgb.width);
    EXPECT_EQ(a.textures[i].srgb.height, b.textures[i].srgb.height);
    EXPECT_EQ(a.textures[i].srgb.rgb, b.textures[i].srgb.rgb);
    EXPECT_EQ(a.textures[i].linear.width, b.textures[i].linear.width);
    EXPECT_EQ(a.textures[i].linear.height, b.textures[i].linear.height);
    expectSameVec3s(a.textures[i].linear.pixels, b.textures[i].linear.pixels);
  }
  EXPECT_EQ(a.warnings, b.warnings);
  EXPECT_EQ(a.notes, b.notes);

  ASSERT_EQ(a.lights.size(), b.lights.size());
  for (size_t i = 0; i < a.lights.size(); ++i) {
    EXPECT_SAME_VEC3(a.lights[i].position, b.lights[i].position);
    EXPECT_SAME_VEC3(a.lights[i].intensity, b.lights[i].intensity);
    EXPECT_SAME_FLOAT(a.lights[i].attenuation.constant, b.lights[i].attenuation.constant);
    EXPECT_SAME_FLOAT(a.lights[i].attenuation.linear, b.lights[i].attenuation.linear);
    EXPECT_SAME_FLOAT(a.lights[i].attenuation.quadratic, b.lights[i].attenuation.quadratic);
    expectSameLoc(a.lights[i].loc, b.lights[i].loc);
  }

  ASSERT_EQ(a.spheres.size(), b.spheres.size());
  for (size_t i = 0; i < a.spheres.size(); ++i) {
    EXPECT_SAME_VEC3(a.spheres[i].center, b.spheres[i].center);
    EXPECT_SAME_FLOAT(a.spheres[i].radius, b.spheres[i].radius);
    EXPECT_EQ(a.spheres[i].material, b.spheres[i].material);
    EXPECT_EQ(a.spheres[i].caustic, b.spheres[i].caustic);
    expectSameLoc(a.spheres[i].loc, b.spheres[i].loc);
  }

  ASSERT_EQ(a.planes.size(), b.planes.size());
  for (size_t i = 0; i < a.planes.size(); ++i) {
    EXPECT_SAME_VEC3(a.planes[i].point, b.planes[i].point);
    EXPECT_SAME_VEC3(a.planes[i].normal, b.planes[i].normal);
    EXPECT_EQ(a.planes[i].material, b.planes[i].material);
    EXPECT_EQ(a.planes[i].caustic, b.planes[i].caustic);
    expectSameLoc(a.planes[i].loc, b.planes[i].loc);
  }

  ASSERT_EQ(a.cones.size(), b.cones.size());
  for (size_t i = 0; i < a.cones.size(); ++i) {
    EXPECT_SAME_VEC3(a.cones[i].base, b.cones[i].base);
    EXPECT_SAME_FLOAT(a.cones[i].baseRadius, b.cones[i].baseRadius);
    EXPECT_SAME_VEC3(a.cones[i].apex, b.cones[i].apex);
    EXPECT_SAME_FLOAT(a.cones[i].apexRadius, b.cones[i].apexRadius);
    EXPECT_EQ(a.cones[i].material, b.cones[i].material);
    EXPECT_EQ(a.cones[i].caustic, b.cones[i].caustic);
    expectSameLoc(a.cones[i].loc, b.cones[i].loc);
  }

  ASSERT_EQ(a.discs.size(), b.discs.size());
  for (size_t i = 0; i < a.discs.size(); ++i) {
    EXPECT_SAME_VEC3(a.discs[i].center, b.discs[i].center);
    EXPECT_SAME_VEC3(a.discs[i].normal, b.discs[i].normal);
    EXPECT_SAME_FLOAT(a.discs[i].radius, b.discs[i].radius);
    EXPECT_EQ(a.discs[i].material, b.discs[i].material);
    EXPECT_EQ(a.discs[i].caustic, b.discs[i].caustic);
    expectSameLoc(a.discs[i].loc, b.discs[i].loc);
  }

  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (size_t i = 0; i < a.meshes.size(); ++i) {
    EXPECT_EQ(a.meshes[i].source, b.meshes[i].source);
    expectSameVec3s(a.meshes[i].positions, b.meshes[i].positions);
    expectSameVec3s(a.meshes[i].normals, b.meshes[i].normals);
    EXPECT_EQ(a.meshes[i].indices, b.meshes[i].indices);
    EXPECT_EQ(a.meshes[i].material, b.meshes[i].material);
    EXPECT_EQ(a.meshes[i].caustic, b.meshes[i].caustic);
    expectSameLoc(a.meshes[i].loc, b.meshes[i].loc);
    ASSERT_EQ(a.meshes[i].uvs.size(), b.meshes[i].uvs.size());
    for (size_t k = 0; k < a.meshes[i].uvs.size(); ++k) {
      EXPECT_SAME_FLOAT(a.meshes[i].uvs[k].x, b.meshes[i].uvs[k].x);
      EXPECT_SAME_FLOAT(a.meshes[i].uvs[k].y, b.meshes[i].uvs[k].y);
    }
    expectSameVec3s(a.meshes[i].colors, b.meshes[i].colors);
    EXPECT_EQ(a.meshes[i].faceMaterials, b.meshes[i].faceMaterials);
  }
}

TEST(SceneCodec, EveryFieldSurvivesTheRoundTrip) {
  const SceneDescription sent = fullScene();
  const SceneDescription back = roundTrip(sent);
  expectSameScene(sent, back);
  EXPECT_EQ(encodeScene(back), encodeScene(sent));
}

TEST(SceneCodec, DefaultSceneRoundTrips) {
  const SceneDescription sent;
  expectSameScene(sent, roundTrip(sent));
}

// Each field list (common/wire/SceneCodec.h) names every field in a structured binding, so a new
// field breaks its build; these sizes catch what the bindings cannot see: a field that the test
// above never sets, or one whose type changed, which changes the wire form without a word.
TEST(SceneCodec, DescriptionStructsMatchTheCodec) {
#if defined(__GLIBCXX__) && UINTPTR_MAX == UINT64_MAX
  const char* update =
      "a SceneDescription struct changed: update its field list (common/wire/SceneCodec.h or "
      "the struct's own) "
      "(and kVersion if its wire form changed), fullScene() and expectSameScene() in this file, "
      "then the size here";
  EXPECT_EQ(sizeof(FileLoc), 40u) << update;
  EXPECT_EQ(sizeof(CameraDesc), 96u) << update;
  EXPECT_EQ(sizeof(Attenuation), 12u) << update;
  EXPECT_EQ(sizeof(PointLightDesc), 80u) << update;
  EXPECT_EQ(sizeof(CheckerDesc), 28u) << update;
  EXPECT_EQ(sizeof(TextureMap), 24u) << update;
  EXPECT_EQ(sizeof(TextureDesc), 96u) << update;
  EXPECT_EQ(sizeof(MaterialDesc), 208u) << update;
  EXPECT_EQ(sizeof(SphereDesc), 72u) << update;
  EXPECT_EQ(sizeof(PlaneDesc), 80u) << update;
  EXPECT_EQ(sizeof(ConeDesc), 88u) << update;
  EXPECT_EQ(sizeof(DiscDesc), 80u) << update;
  EXPECT_EQ(sizeof(MeshDesc), 232u) << update;
  EXPECT_EQ(sizeof(ImageRgb), 32u) << update;
  EXPECT_EQ(sizeof(SrgbImage), 32u) << update;
  EXPECT_EQ(sizeof(CubeMapDesc), 584u) << update;
  EXPECT_EQ(sizeof(RenderSettings), 48u) << update;
  EXPECT_EQ(sizeof(CausticSettings), 88u) << update;
  EXPECT_EQ(sizeof(SceneDescription), 1120u) << update;
#else
  GTEST_SKIP() << "sizes recorded for 64-bit libstdc++";
#endif
}

TEST(SceneCodec, EveryTruncationIsRejected) {
  const std::vector<uint8_t> bytes = payloadOf(fullScene());
  for (size_t length = 0; length < bytes.size(); ++length) {
    const std::vector<uint8_t> prefix(bytes.begin(), bytes.begin() + length);
    EXPECT_THROW(decodeBytes(prefix), WireError) << length;
  }
}

TEST(SceneCodec, UnknownEnumValuesAreRejected) {
  SceneDescription d = fullScene();
  d.camera.projection = static_cast<Projection>(7);
  expectWireError(d, "invalid camera projection 7");
  d = fullScene();
  d.render.triangleTest = static_cast<TriangleTest>(-1);
  expectWireError(d, "invalid triangle test 4294967295");
  d = fullScene();
  d.render.instructionSet = static_cast<InstructionSet>(5);
  expectWireError(d, "invalid instruction set 5");
  d = fullScene();
  d.caustics.method = static_cast<CausticMethod>(3);
  expectWireError(d, "invalid caustic method 3");
  d.caustics.method = CausticMethod::CausticMap;
  d.caustics.mapPaths = static_cast<CausticMapPaths>(2);
  expectWireError(d, "invalid caustic map paths 2");
  d = fullScene();
  d.caustics.filter = static_cast<PhotonFilter>(3);
  expectWireError(d, "invalid photon filter 3");
  d = fullScene();
  d.spheres[1].caustic = static_cast<CausticRole>(5);
  expectWireError(d, "invalid caustic role 5");
  d = fullScene();
  d.meshes[0].caustic = static_cast<CausticRole>(255);
  expectWireError(d, "invalid caustic role 255");
}

// CausticRole is a byte on a u32 field: a value past 255 must not wrap to a valid role.
TEST(SceneCodec, EnumValuesPastANarrowEnumAreNotTruncated) {
  SceneDescription d = fullScene();
  d.spheres[1].caustic = CausticRole::Auto;
  std::vector<uint8_t> bytes = payloadOf(d);
  d.spheres[1].caustic = CausticRole::Cast;
  const std::vector<uint8_t> cast = payloadOf(d);
  ASSERT_EQ(bytes.size(), cast.size());
  const auto role = std::mismatch(bytes.begin(), bytes.end(), cast.begin()).first;
  ASSERT_NE(role, bytes.end());
  *(role + 1) = 1;  // little-endian u32: 0 + 256
  try {
    decodeBytes(bytes);
    ADD_FAILURE() << "no WireError for caustic role 256";
  } catch (const WireError& e) {
    EXPECT_NE(std::string(e.what()).find("invalid caustic role 256"), std::string::npos)
        << e.what();
  }
}

TEST(SceneCodec, CausticSettingsThatCannotRunAreRejected) {
  const std::function<void(CausticSettings&)> spoils[] = {
      [](CausticSettings& c) { c.gather = 0; },   [](CausticSettings& c) { c.maxBounces = 0; },
      [](CausticSettings& c) { c.passes = -3; },  [](CausticSettings& c) { c.maxRadius = -1; },
      [](CausticSettings& c) { c.radius = NAN; }, [](CausticSettings& c) { c.alpha = 0.0f; },
      [](CausticSettings& c) { c.alpha = 1.0f; }, [](CausticSettings& c) { c.alpha = NAN; },
  };
  for (const auto& spoil : spoils) {
    SceneDescription d = fullScene();
    spoil(d.caustics);
    expectWireError(d, "invalid caustic settings");
  }
}

TEST(SceneCodec, MeshesThatWouldReadOutOfBoundsAreRejected) {
  SceneDescription d = fullScene();
  d.meshes[1].indices[1] = 3;
  expectWireError(d,
                  "mesh 1 (everything.yaml:50:7) 'triangle': index 1 is 3, past the 3 positions");
  d = fullScene();
  d.meshes[0].normals.pop_back();
  expectWireError(d, "3 normals for 4 positions");
  d = fullScene();
  d.meshes[0].indices.pop_back();
  expectWireError(d, "5 indices, not a multiple of 3");
  d = fullScene();
  d.meshes[0].uvs.pop_back();
  expectWireError(d, "3 texture coordinates for 4 positions");
  d = fullScene();
  d.meshes[0].colors.push_back(Color(1.0f));
  expectWireError(d, "5 colours for 4 positions");
  d = fullScene();
  d.meshes[0].faceMaterials.pop_back();
  expectWireError(d, "1 face materials for 2 triangles");
  d = fullScene();
  d.meshes[0].faceMaterials[1] = 2;
  expectWireError(d,
                  "mesh 0 (everything.yaml:44:5): a face has material 2 but the scene has 2 "
                  "materials");
}

TEST(SceneCodec, TexturesMustHoldPixelsOfOneKindAndBeNamedByMaps) {
  SceneDescription d = fullScene();
  d.materials[0].diffuseMap->texture = 2;
  expectWireError(d, "material 0 (everything.yaml:10:5): texture 2 but the scene has 2 textures");
  d = fullScene();
  d.textures[0].srgb.rgb.pop_back();
  expectWireError(d, "texture 0 'textures/wood.jpg' is 2x1 but carries 5 bytes");
  d = fullScene();
  d.textures[1].srgb = SrgbImage{1, 1, {1, 2, 3}};
  expectWireError(d, "texture 1 'textures/sky.exr' carries both floats and bytes");
  d = fullScene();
  d.textures[0].srgb = SrgbImage{};
  expectWireError(d, "texture 0 'textures/wood.jpg' is empty");
}

TEST(SceneCodec, MaterialIdsMustNameAMaterial) {
  SceneDescription d = fullScene();
  d.spheres[1].material = 2;
  expectWireError(d, "sphere 1: material 2 but the scene has 2 materials");
  d = fullScene();
  d.planes[0].material = 9;
  expectWireError(d, "plane 0 (everything.yaml:41:5): material 9");
  d = fullScene();
  d.cones[0].material = 2;
  expectWireError(d, "cone 0");
  d = fullScene();
  d.discs[0].material = 2;
  expectWireError(d, "disc 0 (everything.yaml:45:5): material 2");
  d = fullScene();
  d.meshes[1].material = 2;
  expectWireError(d, "mesh 1");
}

// A shape from the wire meets what its keys require in a scene file (geometry/ShapeKeys.h) and
// its own problem(): nothing the parser refuses reaches a build through the wire.
TEST(SceneCodec, ShapesAreCheckedAsTheParserChecksThem) {
  SceneDescription d = fullScene();
  d.spheres[1].radius = 0.0f;
  expectWireError(d, "sphere 1: 'radius' must be a finite number above 0");
  d = fullScene();
  d.discs[0].normal = Vec3(0.0f);
  expectWireError(d, "disc 0 (everything.yaml:45:5): 'normal' must be a finite vector other");
  d = fullScene();
  d.discs[0].center.y = std::numeric_limits<float>::infinity();
  expectWireError(d, "disc 0 (everything.yaml:45:5): 'center' must be finite");
  d = fullScene();
  d.cones[1].apex = d.cones[1].base;
  expectWireError(d, "cone 1 (everything.yaml:43:5): 'apex' must differ from 'base'");
  d = fullScene();
  d.cones[0].baseRadius = d.cones[0].apexRadius = 0.0f;
  expectWireError(d, "cone 0 (everything.yaml:42:5): a cone needs 'base_radius' or");
  d = fullScene();
  d.cones[0].apexRadius = -1.0f;
  expectWireError(d, "cone 0 (everything.yaml:42:5): 'apex_radius' must be a finite number of");
}

// Scene supplies a default material when the list is empty, so id 0 is valid then.
TEST(SceneCodec, MaterialZeroIsValidWithoutMaterials) {
  SceneDescription d = fullScene();
  d.materials.clear();
  forEachShapeList(d, [](auto& shapes) {
    for (auto& shape : shapes) shape.material = 0;
  });
  for (auto& p : d.planes) p.material = 0;
  for (auto& m : d.meshes) {
    m.material = 0;
    m.faceMaterials.clear();
  }
  EXPECT_NO_THROW(decodeBytes(payloadOf(d)));
  d.meshes[0].material = 1;
  expectWireError(d, "mesh 0 (everything.yaml:44:5): material 1 but the scene has 0 materials");
}

TEST(SceneCodec, ImagesMustHoldWidthTimesHeightPixels) {
  SceneDescription d = fullScene();
  d.environment->faces[3].pixels.pop_back();
  expectWireError(d, "cube-map face 3 is 2x2 but carries 3 pixels");
  d = fullScene();
  d.environment->faces[2] = ImageRgb();
  expectWireError(d, "cube-map face 2 is empty");
  d = fullScene();
  d.environment->faces[1].width = -2;
  d.environment->faces[1].height = -2;
  expectWireError(d, "cube-map face 1 has negative size -2x-2");
}

// fullScene()'s cube map with its faces as 8-bit bytes.
SceneDescription sceneWithByteFaces() {
  SceneDescription d = fullScene();
  for (int i = 0; i < 6; ++i) {
    const int size = i % 2 + 1;
    d.environment->faces[i] = ImageRgb();
    d.environment->srgbFaces[i] = SrgbImage{size, size, {}};
    for (int b = 0; b < 3 * size * size; ++b) {
      d.environment->srgbFaces[i].rgb.push_back(static_cast<uint8_t>(40 * i + b));
    }
  }
  return d;
}

TEST(SceneCodec, CubeMapFacesTravelAsBytes) {
  const SceneDescription d = sceneWithByteFaces();
  const SceneDescription back = decodeBytes(payloadOf(d));
  ASSERT_TRUE(back.environment && back.environment->keptAsBytes());
  expectSameScene(d, back);
}

TEST(SceneCodec, CubeMapFacesAreAllFloatsOrAllBytes) {
  SceneDescription d = sceneWithByteFaces();
  d.environment->srgbFaces[4].rgb.pop_back();
  expectWireError(d, "cube-map face 4 is 1x1 but carries 2 bytes");
  d = sceneWithByteFaces();
  d.environment->faces[2] = ImageRgb(1, 1);
  expectWireError(d, "cube-map face 2 carries both floats and bytes");
  d = sceneWithByteFaces();
  d.environment->srgbFaces[5] = SrgbImage();
  d.environment->faces[5] = ImageRgb(2, 2);
  expectWireError(d, "cube-map face 5 is not of face 0's kind");
  d = fullScene();
  d.environment->faces[3] = ImageRgb();
  d.environment->srgbFaces[3] = SrgbImage{2, 2, std::vector<uint8_t>(12)};
  expectWireError(d, "cube-map face 3 is not of face 0's kind");
  d = sceneWithByteFaces();
  d.environment->srgbFaces[1] = SrgbImage();
  expectWireError(d, "cube-map face 1 is empty");
}

TEST(SceneCodec, RenderSettingsThatCannotRenderAreRejected) {
  SceneDescription d = fullScene();
  d.render.width = 0;
  expectWireError(d, "invalid render settings: render setting 'width' must be at least 1, found 0");
  d = fullScene();
  d.render.samplesPerPixel = 0;
  expectWireError(d, "render setting 'samples' must be at least 1, found 0 (--spp on the");
  d = fullScene();
  d.render.maxDepth = -1;
  expectWireError(d, "render setting 'max_depth' must be at least 0, found -1");
  // The same bound as the scene parser and the command line (scene/SettingLimits.h).
  d = fullScene();
  d.render.maxDepth = 257;
  expectWireError(d, "render setting 'max_depth' must be at most 256, found 257 (--max-depth");
  d = fullScene();
  d.caustics.mapResolution = 8;
  expectWireError(d,
                  "invalid caustic settings: caustics setting 'map_resolution' must be at "
                  "least 16, found 8");
}

TEST(SceneCodec, HugeCorruptedCountThrowsWithoutAllocating) {
  SceneDescription d;
  d.meshes.resize(1);
  std::vector<uint8_t> bytes = payloadOf(d);
  // The empty mesh, then the warnings and notes counts (8 + 8), end the payload. The mesh:
  // source (4-byte length), positions count (8), normals count (8), indices count (8), material
  // (4), caustic role (4), loc (4 + 4 + 4), uvs, colours and face materials counts (8 + 8 + 8).
  const size_t positionsCount = bytes.size() - 16 - 72 + 4;
  ASSERT_EQ(std::count(bytes.begin() + positionsCount, bytes.begin() + positionsCount + 8, 0), 8);
  bytes[positionsCount + 7] = 0x10;  // 2^60
  try {
    decodeBytes(bytes);
    FAIL() << "corrupted count accepted";
  } catch (const WireError& e) {
    EXPECT_NE(std::string(e.what()).find("corrupt element count 1152921504606846976"),
              std::string::npos)
        << e.what();
  }
}

TEST(SceneCodec, SceneMessageIsCheckedLikeAnyOther) {
  std::vector<uint8_t> bytes = encodeScene(fullScene());
  EXPECT_THROW(decode<TileJobMessage>(decodeMessage(bytes)), WireError);
  bytes[kHeaderSize + 10] ^= 0x20;
  EXPECT_THROW(decodeMessage(bytes), WireError);
}

std::vector<std::string> realSceneFiles() {
  std::vector<std::string> files = {std::string(PRISM_SOURCE_DIR) + "/scenes/default.yaml"};
  for (const auto& entry :
       std::filesystem::directory_iterator(std::string(PRISM_TEST_DATA_DIR) + "/scenes")) {
    if (entry.path().extension() == ".yaml") files.push_back(entry.path().string());
  }
  std::sort(files.begin() + 1, files.end());
  return files;
}

TEST(SceneCodec, RealSceneFilesRoundTripByteForByte) {
  const std::vector<std::string> files = realSceneFiles();
  ASSERT_GE(files.size(), 3u);
  for (const std::string& path : files) {
    SCOPED_TRACE(path);
    const SceneDescription loaded = loadScene(path);
    const std::vector<uint8_t> bytes = encodeScene(loaded);
    const SceneDescription back = decodeScene(decodeMessage(bytes));
    expectSameScene(loaded, back);
    EXPECT_EQ(encodeScene(back), bytes);
  }
}

}  // namespace
}  // namespace prism::wire
