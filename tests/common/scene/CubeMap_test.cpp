#include "scene/CubeMap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "math/Random.h"

namespace prism {
namespace {

// Each face is filled with its own colour, plus a marker in the top-left texel.
CubeMapDesc labelledCube() {
  CubeMapDesc d;
  for (int f = 0; f < 6; ++f) {
    d.faces[f] = ImageRgb(4, 4);
    for (Color& c : d.faces[f].pixels) c = Color(static_cast<float>(f), 0.0f, 0.0f);
  }
  return d;
}

TEST(CubeMap, AxisDirectionsSelectTheOpenGLFaces) {
  const CubeMap cube(labelledCube());
  const Vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int f = 0; f < 6; ++f) EXPECT_FLOAT_EQ(cube.lookup(axes[f]).x, static_cast<float>(f));
}

TEST(CubeMap, FaceOrientationFollowsTheOpenGLTable) {
  // On +Z, the image's top-left corner is seen towards (-x, +y); on +Y it is towards (-x, -z).
  CubeMapDesc d = labelledCube();
  d.faces[4].at(0, 0) = Color(0, 1, 0);
  d.faces[2].at(0, 0) = Color(0, 0, 1);
  const CubeMap cube(d);
  EXPECT_NEAR(cube.lookup({-0.99f, 0.99f, 1.0f}).y, 1.0f, 1e-4f);
  EXPECT_NEAR(cube.lookup({0.99f, -0.99f, 1.0f}).y, 0.0f, 1e-4f);
  EXPECT_NEAR(cube.lookup({-0.99f, 1.0f, -0.99f}).z, 1.0f, 1e-4f);
}

TEST(CubeMap, ScaleMultipliesRadiance) {
  CubeMapDesc d = labelledCube();
  d.scale = 2.5f;
  EXPECT_FLOAT_EQ(CubeMap(d).lookup({0, 0, -1}).x, 12.5f);
}

// Bilinear filtering written out the plain way: every texel clamped into the face, blended
// with glm::mix. CubeMap::lookup reads interior texels without clamping and blends them as
// vector lanes; it must give these very floats.
Color referenceLookup(const CubeMap& cube, const CubeMapDesc& d, const Vec3& dir) {
  const CubeMap::FacePoint p = *cube.facePoint(dir);
  const ImageRgb& image = d.faces[p.face];
  const int x0 = static_cast<int>(std::floor(p.s)), y0 = static_cast<int>(std::floor(p.t));
  const float fx = p.s - static_cast<float>(x0), fy = p.t - static_cast<float>(y0);
  const auto texel = [&](int x, int y) {
    return image.at(std::clamp(x, 0, image.width - 1), std::clamp(y, 0, image.height - 1));
  };
  const Color top = glm::mix(texel(x0, y0), texel(x0 + 1, y0), fx);
  const Color bottom = glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), fx);
  return d.scale * glm::mix(top, bottom, fy);
}

bool sameBits(const Color& a, const Color& b) {
  return std::memcmp(&a, &b, sizeof(Color)) == 0;
}

TEST(CubeMap, BilinearLookupMatchesThePlainFormulaBitForBit) {
  // Faces of 5x3 texels with values of every magnitude, so a mixed-up width and height, a
  // texel read from the wrong row or a blend done in another order shows in the last bit.
  CubeMapDesc d;
  d.scale = 0.7f;
  Pcg32 rng(7, 11);
  for (ImageRgb& face : d.faces) {
    face = ImageRgb(5, 3);
    for (Color& c : face.pixels) {
      c = Color(rng.nextFloat(), 100.0f * rng.nextFloat(), 1e-3f * rng.nextFloat());
    }
  }
  const CubeMap cube(d);
  int mismatches = 0;
  // Directions over every face, its edges and corners included (the clamped texels).
  for (int i = 0; i < 20000; ++i) {
    const Vec3 dir(2.0f * rng.nextFloat() - 1.0f, 2.0f * rng.nextFloat() - 1.0f,
                   2.0f * rng.nextFloat() - 1.0f);
    if (glm::length(dir) == 0.0f) continue;
    mismatches += !sameBits(cube.lookup(dir), referenceLookup(cube, d, dir));
  }
  for (int f = 0; f < 6; ++f) {
    for (const float u : {-1.0f, -0.999f, 0.0f, 0.999f, 1.0f}) {
      for (const float v : {-1.0f, -0.999f, 0.0f, 0.999f, 1.0f}) {
        const float major = f % 2 ? -1.0f : 1.0f;  // the face's axis, its sign
        const Vec3 dir = f / 2 == 0   ? Vec3(major, u, v)
                         : f / 2 == 1 ? Vec3(u, major, v)
                                      : Vec3(u, v, major);
        mismatches += !sameBits(cube.lookup(dir), referenceLookup(cube, d, dir));
      }
    }
  }
  EXPECT_EQ(mismatches, 0);
}

}  // namespace
}  // namespace prism
