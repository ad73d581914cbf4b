#include "scene/CubeMap.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace prism
