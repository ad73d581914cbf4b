#include "scene/Texture.h"

#include <gtest/gtest.h>

#include <cmath>

#include "image/SrgbImage.h"
#include "math/RayCone.h"
#include "shading/MaterialEval.h"

namespace prism {
namespace {

// A width × height texture of sRGB bytes, texel (x, y) (row y from the top) of byte value
// value(x, y) in all three channels.
template <class Value>
TextureDesc byteTexture(int width, int height, Value value) {
  TextureDesc t;
  t.path = "test.png";
  t.srgb.width = width;
  t.srgb.height = height;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const uint8_t v = value(x, y);
      t.srgb.rgb.insert(t.srgb.rgb.end(), {v, v, v});
    }
  }
  return t;
}

float linear(uint8_t byte) {
  return linearOfSrgbByte()[byte];
}

TEST(Texture, TexelCentresReadTheirTexelWithVZeroAtTheBottomRow) {
  // Row 0 (top) is 10, 20; row 1 (bottom) is 30, 40.
  const Texture texture(byteTexture(2, 2, [](int x, int y) { return 10 * (1 + x + 2 * y); }));
  EXPECT_FLOAT_EQ(texture.lookup({0.25f, 0.75f}, 0.0f).x, linear(10));
  EXPECT_FLOAT_EQ(texture.lookup({0.75f, 0.75f}, 0.0f).x, linear(20));
  EXPECT_FLOAT_EQ(texture.lookup({0.25f, 0.25f}, 0.0f).x, linear(30));
  EXPECT_FLOAT_EQ(texture.lookup({0.75f, 0.25f}, 0.0f).y, linear(40));
}

TEST(Texture, CoordinatesRepeat) {
  const Texture texture(byteTexture(4, 4, [](int x, int y) { return 17 * x + 61 * y; }));
  for (const Vec2 uv : {Vec2(0.1f, 0.2f), Vec2(0.9f, 0.05f), Vec2(0.5f, 0.99f)}) {
    const Color here = texture.lookup(uv, 0.0f);
    for (const Vec2 shift : {Vec2(1, 0), Vec2(-3, 2), Vec2(0, -1)}) {
      const Color there = texture.lookup(uv + shift, 0.0f);
      EXPECT_NEAR(there.x, here.x, 1e-5f) << uv.x << "," << uv.y << " + " << shift.x;
    }
  }
  // Between the last texel and the first the bilinear blend wraps: halfway is their mean.
  const Texture ramp(
      byteTexture(4, 1, [](int x, int) { return x == 0 ? 200 : (x == 3 ? 0 : 90); }));
  EXPECT_NEAR(ramp.lookup({1.0f, 0.5f}, 0.0f).x, 0.5f * linear(200), 1e-6f);
}

TEST(Texture, TheFootprintChoosesTheLevel) {
  const Texture texture(byteTexture(64, 64, [](int x, int y) { return ((x + y) & 1) ? 255 : 0; }));
  ASSERT_EQ(texture.levelCount(), 7);
  EXPECT_FLOAT_EQ(texture.levelOfDetail(1.0f / 64.0f), 0.0f);  // a texel: the finest
  EXPECT_FLOAT_EQ(texture.levelOfDetail(4.0f / 64.0f), 2.0f);
  EXPECT_FLOAT_EQ(texture.levelOfDetail(0.25f / 64.0f), 0.0f);  // magnified: the finest
  // Between levels the lookup blends the two about the level of detail.
  const Vec2 uv(0.3f, 0.6f);
  const float width = 6.0f / 64.0f;  // log2(6) = 2.585
  const float lod = std::log2(6.0f);
  const Color expected = glm::mix(texture.bilinear(2, uv), texture.bilinear(3, uv), lod - 2.0f);
  EXPECT_NEAR(texture.lookup(uv, width).x, expected.x, 1e-6f);
  // A footprint over the whole texture reads its mean: the 1×1 top level, half of each.
  const float mean = 0.5f * (linear(255) + linear(0));
  EXPECT_NEAR(texture.lookup(uv, 2.0f).x, mean, 4e-3f);  // kept as the nearest byte
}

TEST(Texture, LinearImagesKeepTheirValues) {
  TextureDesc t;
  t.path = "hdr.exr";
  t.linear = ImageRgb(2, 1);
  t.linear.at(0, 0) = Color(4.0f, 0.5f, 0.0f);
  t.linear.at(1, 0) = Color(0.0f, 0.0f, 8.0f);
  const Texture texture(t);
  EXPECT_FALSE(texture.keepsBytes());
  EXPECT_EQ(texture.lookup({0.25f, 0.5f}, 0.0f), Color(4.0f, 0.5f, 0.0f));
  EXPECT_EQ(texture.lookup({0.75f, 0.5f}, 0.0f), Color(0.0f, 0.0f, 8.0f));
}

TEST(MaterialEval, TheTextureAndTheVertexColourMultiplyTheDiffuseColour) {
  std::vector<Texture> textures;
  textures.emplace_back(byteTexture(2, 2, [](int x, int) { return x == 0 ? 255 : 128; }));
  MaterialDesc m;
  m.diffuse = Color(0.5f, 1.0f, 1.0f);
  m.diffuseMap = TextureMap{};
  SurfaceHit s;
  s.geometricNormal = Vec3(0, 0, 1);
  s.uv = Vec2(0.25f, 0.25f);
  s.uvPerWorld = 1.0f;
  s.vertexColor = Color(1.0f, 0.5f, 0.25f);
  const Vec3 d(0, 0, -1);
  EXPECT_EQ(diffuseAlbedo(m, s, textures, d, 0.0f), Color(0.5f, 0.5f, 0.25f));
  s.uv = Vec2(0.75f, 0.25f);
  const float half = linear(128);
  const Color c = diffuseAlbedo(m, s, textures, d, 0.0f);
  EXPECT_FLOAT_EQ(c.x, 0.5f * half);
  EXPECT_FLOAT_EQ(c.z, 0.25f * half);
  // A surface without texture coordinates keeps the diffuse colour.
  s.uvPerWorld = -1.0f;
  EXPECT_EQ(diffuseAlbedo(m, s, textures, d, 0.0f), Color(0.5f, 0.5f, 0.25f));
}

TEST(MaterialEval, TheMapsTransformMovesScalesAndTurnsTheCoordinates) {
  TextureMap map;
  map.scale = Vec2(2.0f, 3.0f);
  map.offset = Vec2(0.5f, -0.25f);
  const Vec2 q = mappedCoordinates(map, Vec2(0.25f, 0.5f));
  EXPECT_FLOAT_EQ(q.x, 1.0f);
  EXPECT_FLOAT_EQ(q.y, 1.25f);
  map = TextureMap{};
  map.rotation = 0.5f * kPi;  // a quarter turn counter-clockwise: (1, 0) to (0, 1)
  const Vec2 turned = mappedCoordinates(map, Vec2(1.0f, 0.0f));
  EXPECT_NEAR(turned.x, 0.0f, 1e-6f);
  EXPECT_NEAR(turned.y, 1.0f, 1e-6f);
}

TEST(RayCone, WidthGrowsWithDistanceAndCurvedMirrorsSpreadIt) {
  const RayCone pixel{0.0f, 0.01f};
  EXPECT_TRUE(pixel.known());
  EXPECT_FALSE(RayCone{}.known());
  EXPECT_FLOAT_EQ(pixel.widthAt(10.0f), 0.1f);
  // A flat mirror passes the cone on: 10 more units give the width of 20.
  const RayCone flat = pixel.reflected(10.0f, 0.0f);
  EXPECT_FLOAT_EQ(flat.widthAt(10.0f), pixel.widthAt(20.0f));
  // A convex mirror (curvature +1/R) spreads it by twice its width over R.
  const RayCone convex = pixel.reflected(10.0f, 1.0f / 0.5f);
  EXPECT_FLOAT_EQ(convex.spread, 0.01f + 2.0f * 0.1f / 0.5f);
  // A concave one focuses it: the width passes through zero and grows again.
  const RayCone concave = pixel.reflected(10.0f, -1.0f / 0.5f);
  EXPECT_LT(concave.spread, 0.0f);
  EXPECT_NEAR(concave.widthAt(0.1f / -concave.spread), 0.0f, 1e-6f);
}

}  // namespace
}  // namespace prism
