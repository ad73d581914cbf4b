#include "parse/GltfMaterial.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/parse/GltfAssets.h"

namespace prism {
namespace {

using gltftest::GltfAssets;

MaterialDesc materialOf(const std::string& json, std::vector<std::string>* warnings = nullptr) {
  GltfAssets a;
  const std::string body = gltftest::oneTriangle(a, "", ",\"materials\":[" + json + "]");
  std::string withMaterial = body;
  withMaterial.replace(withMaterial.find("}}]}]"), 5, "},\"material\":0}]}]");
  ModelDesc model = gltftest::parse(a.gltf(withMaterial));
  if (warnings) *warnings = model.warnings;
  EXPECT_EQ(model.materials.size(), 1u);
  return model.materials.at(0);
}

void expectColor(const Color& c, float r, float g, float b) {
  EXPECT_NEAR(c.r, r, 1e-5f);
  EXPECT_NEAR(c.g, g, 1e-5f);
  EXPECT_NEAR(c.b, b, 1e-5f);
}

TEST(GltfMaterial, HalfMetallicRoughnessHalfFollowsTheDocumentedRule) {
  const MaterialDesc m = materialOf(
      "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.8,0.4,0.2,1],\"metallicFactor\":0.5,"
      "\"roughnessFactor\":0.5}}");
  expectColor(m.diffuse, 0.4f, 0.2f, 0.1f);  // base × (1 − metallic)
  expectColor(m.ambient, 0.4f, 0.2f, 0.1f);
  expectColor(m.reflectance, 0.4f, 0.2f, 0.1f);  // metallic × base
  // α = 0.25: Blinn-Phong 2/α² − 2 = 30, as a Phong exponent 7.5.
  EXPECT_NEAR(m.shininess, 7.5f, 1e-4f);
  const float norm = (7.5f + 2.0f) / (2.0f * std::numbers::pi_v<float>);
  expectColor(m.specular, 0.42f * norm, 0.22f * norm, 0.12f * norm);  // mix(0.04, base, 0.5)
  expectColor(m.transmittance, 0, 0, 0);
}

TEST(GltfMaterial, DefaultsAreAWhiteRoughMetalAndSmoothSurfacesClampTheExponent) {
  const MaterialDesc metal = materialOf("{}");
  expectColor(metal.diffuse, 0, 0, 0);
  expectColor(metal.reflectance, 1, 1, 1);
  EXPECT_EQ(metal.shininess, 1.0f);  // roughness 1: the widest lobe
  const MaterialDesc smooth =
      materialOf("{\"pbrMetallicRoughness\":{\"metallicFactor\":0,\"roughnessFactor\":0}}");
  EXPECT_EQ(smooth.shininess, 4096.0f);
  expectColor(smooth.diffuse, 1, 1, 1);
}

TEST(GltfMaterial, TransmissionAndIorMakeGlass) {
  const MaterialDesc glass = materialOf(
      "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,1,0.5,1],\"metallicFactor\":0,"
      "\"roughnessFactor\":0},\"extensions\":{\"KHR_materials_transmission\":"
      "{\"transmissionFactor\":1},\"KHR_materials_ior\":{\"ior\":1.33}}}");
  expectColor(glass.transmittance, 1, 1, 0.5f);
  expectColor(glass.diffuse, 0, 0, 0);
  EXPECT_NEAR(glass.ior, 1.33f, 1e-6f);
  EXPECT_TRUE(glass.fresnel);
}

TEST(GltfMaterial, WhatIsNotModelledIsNamedOnce) {
  std::vector<std::string> warnings;
  materialOf(
      "{\"emissiveFactor\":[1,0,0],\"alphaMode\":\"BLEND\",\"extensions\":"
      "{\"KHR_materials_clearcoat\":{}}}",
      &warnings);
  ASSERT_EQ(warnings.size(), 3u);
  EXPECT_EQ(warnings[0],
            "model.gltf: materials[0].emissiveFactor: emission is not modelled: the "
            "surface does not glow");
  EXPECT_NE(warnings[1].find("alphaMode BLEND"), std::string::npos);
  EXPECT_NE(warnings[2].find("KHR_materials_clearcoat: not modelled"), std::string::npos);
}

// glTF's lookup of KHR_texture_transform (offset + R(θ)·S·uv, v down, R as the extension's
// GLSL builds it) and Prism's TextureMap on the flipped coordinates read the same texel.
TEST(GltfMaterial, TextureTransformsReadTheSameTexelAfterTheVFlip) {
  const Vec2 offset(0.25f, -0.4f), scale(1.5f, 0.75f);
  const float rotation = 0.392699f;
  const TextureMap map = gltfTextureTransform(offset, rotation, scale);
  auto wrap = [](float x) { return x - std::floor(x); };
  for (const Vec2 uv : {Vec2(0.1f, 0.2f), Vec2(0.7f, 0.9f), Vec2(0.5f, 0.5f)}) {
    const float c = std::cos(rotation), s = std::sin(rotation);
    const Vec2 scaled = uv * scale;
    // mat3(cos, sin, 0, -sin, cos, 0, ...) is column-major: x' = c·x − s·y, y' = s·x + c·y.
    const Vec2 gltf = offset + Vec2(c * scaled.x - s * scaled.y, s * scaled.x + c * scaled.y);
    const Vec2 prismUv(uv.x, 1.0f - uv.y);
    const float pc = std::cos(map.rotation), ps = std::sin(map.rotation);
    const Vec2 ps2 = prismUv * map.scale;
    const Vec2 prism = map.offset + Vec2(pc * ps2.x - ps * ps2.y, ps * ps2.x + pc * ps2.y);
    EXPECT_NEAR(wrap(prism.x), wrap(gltf.x), 1e-5f);
    EXPECT_NEAR(wrap(prism.y), wrap(1.0f - gltf.y), 1e-5f);
  }
}

}  // namespace
}  // namespace prism
