#include "scene/CubeMap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "image/SrgbImage.h"
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
  // The directions through the centres of those texels (4 x 4 faces: at ±0.75 on the face).
  EXPECT_NEAR(cube.lookup({-0.75f, 0.75f, 1.0f}).y, 1.0f, 1e-4f);
  EXPECT_NEAR(cube.lookup({0.75f, -0.75f, 1.0f}).y, 0.0f, 1e-4f);
  EXPECT_NEAR(cube.lookup({-0.75f, 1.0f, -0.75f}).z, 1.0f, 1e-4f);
}

TEST(CubeMap, ScaleMultipliesRadiance) {
  CubeMapDesc d = labelledCube();
  d.scale = 2.5f;
  EXPECT_FLOAT_EQ(CubeMap(d).lookup({0, 0, -1}).x, 12.5f);
}

// The texel a bilinear blend reads at (x, y) of a face, x or y possibly one past the face's
// edge: there, the nearest texel of the face the direction through it meets.
Color seamlessTexel(const CubeMap& cube, const CubeMapDesc& d, int face, int x, int y) {
  const ImageRgb& image = d.faces[face];
  const bool inX = x >= 0 && x < image.width, inY = y >= 0 && y < image.height;
  if (inX && inY) return image.at(x, y);
  if (!inX && !inY) {  // past a corner: the three texels about it, averaged
    const int cx = std::clamp(x, 0, image.width - 1), cy = std::clamp(y, 0, image.height - 1);
    return (image.at(cx, cy) + seamlessTexel(cube, d, face, x, cy) +
            seamlessTexel(cube, d, face, cx, y)) /
           3.0f;
  }
  // The face's point (sc, tc) / |ma| in [-1, 1] and the direction through it, from the
  // OpenGL table read backwards.
  const float u = 2.0f * (static_cast<float>(x) + 0.5f) / static_cast<float>(image.width) - 1.0f;
  const float v = 2.0f * (static_cast<float>(y) + 0.5f) / static_cast<float>(image.height) - 1.0f;
  const Vec3 directions[6] = {{1, -v, -u}, {-1, -v, u}, {u, 1, v},
                              {u, -1, -v}, {u, -v, 1},  {-u, -v, -1}};
  const CubeMap::FacePoint q = *cube.facePoint(directions[face]);
  const ImageRgb& next = d.faces[q.face];
  return next.at(std::clamp(static_cast<int>(std::floor(q.s + 0.5f)), 0, next.width - 1),
                 std::clamp(static_cast<int>(std::floor(q.t + 0.5f)), 0, next.height - 1));
}

// Bilinear filtering written out the plain way: every texel fetched alone (past an edge from
// the neighbouring face), blended with glm::mix. CubeMap::lookup reads interior texels as
// vector lanes; it must give these very floats.
Color referenceLookup(const CubeMap& cube, const CubeMapDesc& d, const Vec3& dir) {
  const CubeMap::FacePoint p = *cube.facePoint(dir);
  const int x0 = static_cast<int>(std::floor(p.s)), y0 = static_cast<int>(std::floor(p.t));
  const float fx = p.s - static_cast<float>(x0), fy = p.t - static_cast<float>(y0);
  const auto texel = [&](int x, int y) { return seamlessTexel(cube, d, p.face, x, y); };
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
  // Directions over every face, its edges and corners included (the neighbours' texels).
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

// Faces of size × size texels, each texel the value of f at the direction through its centre.
template <class F>
CubeMapDesc bakedCube(int size, F f) {
  CubeMapDesc d;
  const CubeMap labels(labelledCube());  // only for its face table, via facePoint
  for (int face = 0; face < 6; ++face) {
    d.faces[face] = ImageRgb(size, size);
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) {
        const float u = 2.0f * (static_cast<float>(x) + 0.5f) / static_cast<float>(size) - 1.0f;
        const float v = 2.0f * (static_cast<float>(y) + 0.5f) / static_cast<float>(size) - 1.0f;
        const Vec3 directions[6] = {{1, -v, -u}, {-1, -v, u}, {u, 1, v},
                                    {u, -1, -v}, {u, -v, 1},  {-u, -v, -1}};
        d.faces[face].at(x, y) = f(glm::normalize(directions[face]));
      }
    }
  }
  return d;
}

// A ray's per-pixel direction steps, both `angle` long and across d.
struct Steps {
  Vec3 dx, dy;
};
Steps stepsAcross(const Vec3& d, float angle) {
  const Vec3 side =
      glm::normalize(glm::cross(d, std::fabs(d.y) < 0.9f ? Vec3(0, 1, 0) : Vec3(1, 0, 0)));
  return {angle * side, angle * glm::cross(d, side)};
}

TEST(CubeMap, AZeroFootprintReadsTheFinestLevelBitForBit) {
  CubeMapDesc d;
  d.scale = 1.3f;
  Pcg32 rng(5, 2);
  for (ImageRgb& face : d.faces) {
    face = ImageRgb(16, 16);
    for (Color& c : face.pixels)
      c = Color(rng.nextFloat(), rng.nextFloat(), 4.0f * rng.nextFloat());
  }
  const CubeMap cube(d);
  ASSERT_EQ(cube.levelCount(), 5);
  int mismatches = 0;
  for (int i = 0; i < 5000; ++i) {
    const Vec3 dir =
        glm::normalize(Vec3(2.0f * rng.nextFloat() - 1.0f, 2.0f * rng.nextFloat() - 1.0f,
                            2.0f * rng.nextFloat() - 1.0f));
    const Color finest = cube.lookup(dir);
    mismatches += !sameBits(cube.lookup(dir, Vec3(0.0f), Vec3(0.0f)), finest);
    // A step of half a texel (a face spans about 2/16 radians per texel at its centre)
    // still magnifies the finest level.
    const Steps small = stepsAcross(dir, 0.02f);
    mismatches += !sameBits(cube.lookup(dir, small.dx, small.dy), finest);
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_EQ(cube.levelOfDetail({0, 0, -1}, Vec3(0.0f), Vec3(0.0f)), -INFINITY);
}

TEST(CubeMap, LevelOfDetailIsTheFootprintInTexels) {
  // At a face's centre a step of angle a across it moves the point by a·size/2 texels (to first
  // order); λ = log2 of that, growing with the footprint wherever the direction points.
  const CubeMap cube(bakedCube(64, [](const Vec3&) { return Color(1.0f); }));
  for (const float a : {1e-3f, 0.01f, 0.1f}) {
    EXPECT_NEAR(cube.levelOfDetail({0, 0, -1}, {a, 0, 0}, {0, 0, 0}), std::log2(a * 32.0f), 1e-4f);
    EXPECT_NEAR(cube.levelOfDetail({0, 1, 0}, {0, 0, 0}, {0, 0, a}), std::log2(a * 32.0f), 1e-4f);
  }
  Pcg32 rng(3, 3);
  for (int i = 0; i < 200; ++i) {
    const Vec3 dir =
        glm::normalize(Vec3(2.0f * rng.nextFloat() - 1.0f, 2.0f * rng.nextFloat() - 1.0f,
                            2.0f * rng.nextFloat() - 1.0f));
    float previous = -INFINITY;
    for (float angle = 1e-4f; angle < 1.0f; angle *= 1.5f) {
      const Steps steps = stepsAcross(dir, angle);
      const float lod = cube.levelOfDetail(dir, steps.dx, steps.dy);
      EXPECT_GT(lod, previous) << i << " at " << angle;
      previous = lod;
    }
  }
}

TEST(CubeMap, FootprintsBlendTheTwoLevelsAboutTheirLevelOfDetail) {
  CubeMapDesc d;
  Pcg32 rng(8, 1);
  for (ImageRgb& face : d.faces) {
    face = ImageRgb(32, 32);
    for (Color& c : face.pixels) c = Color(rng.nextFloat(), rng.nextFloat(), rng.nextFloat());
  }
  const CubeMap cube(d);
  // The -Z face's centre, u = v = 0.5 on it, with λ = 2.5: halfway between levels 2 and 3.
  const float angle = std::exp2(2.5f) / 16.0f;
  const Vec3 dir(0, 0, -1);
  ASSERT_NEAR(cube.levelOfDetail(dir, {angle, 0, 0}, {0, angle, 0}), 2.5f, 1e-5f);
  const Color expected =
      glm::mix(cube.bilinear(2, 5, 0.5f, 0.5f), cube.bilinear(3, 5, 0.5f, 0.5f), 0.5f);
  const Color got = cube.lookup(dir, {angle, 0, 0}, {0, angle, 0});
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], 1e-5f);

  // A footprint wider than the face reads the face's mean (the 1x1 level) at its centre.
  const Color mean = cube.texelAt(cube.levelCount() - 1, 5, 0, 0);
  glm::dvec3 sum(0.0);
  for (const Color& c : d.faces[5].pixels) sum += glm::dvec3(c);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean[c], sum[c] / (32.0 * 32.0), 1e-5);
  const Color wide = cube.lookup(dir, {3.0f, 0, 0}, {0, 3.0f, 0});
  for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(wide[c], mean[c]);
}

TEST(CubeMap, FacesKeptAsBytesReadAsTheirRadiance) {
  // The same random 8-bit faces kept as bytes and as decoded floats: the finest level's lookups
  // agree bit for bit (the same radiance blended the same way), the coarser levels to within half
  // an sRGB step of the brightest texel (each level rounded to bytes once, from floats).
  CubeMapDesc bytes, floats;
  Pcg32 rng(12, 5);
  for (int f = 0; f < 6; ++f) {
    bytes.srgbFaces[f] = SrgbImage{16, 16, {}};
    for (int i = 0; i < 3 * 16 * 16; ++i) {
      bytes.srgbFaces[f].rgb.push_back(static_cast<uint8_t>(rng.nextUint() & 0xff));
    }
    floats.faces[f] = linearFromSrgb(bytes.srgbFaces[f]);
  }
  bytes.scale = floats.scale = 1.5f;
  ASSERT_TRUE(bytes.keptAsBytes());
  const CubeMap fromBytes(bytes), fromFloats(floats);
  EXPECT_TRUE(fromBytes.keepsBytes());
  EXPECT_FALSE(fromFloats.keepsBytes());
  ASSERT_EQ(fromBytes.levelCount(), fromFloats.levelCount());
  int mismatches = 0;
  float worst = 0.0f;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 dir =
        glm::normalize(Vec3(2.0f * rng.nextFloat() - 1.0f, 2.0f * rng.nextFloat() - 1.0f,
                            2.0f * rng.nextFloat() - 1.0f));
    mismatches += !sameBits(fromBytes.lookup(dir), fromFloats.lookup(dir));
    const Steps wide = stepsAcross(dir, 0.05f + 0.5f * rng.nextFloat());
    const Color a = fromBytes.lookup(dir, wide.dx, wide.dy);
    const Color b = fromFloats.lookup(dir, wide.dx, wide.dy);
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::fabs(a[c] - b[c]));
  }
  EXPECT_EQ(mismatches, 0);
  // Half a byte's step at the top of the range, 0.0045, times the scale.
  EXPECT_LT(worst, 1.5f * 0.0045f);
  EXPECT_GT(worst, 0.0f);  // the coarse levels are rounded
}

TEST(CubeMap, LookupsAreContinuousAcrossFaceEdges) {
  // A sky that varies smoothly with direction: on either side of an edge, at every level, the
  // two faces' lookups agree to within what the sky changes over a fraction of that level's
  // texel. Blends clamped to each face's own texels (no neighbour read) differ by the change
  // over a whole texel there, up to 0.4 at the coarse levels.
  const auto sky = [](const Vec3& d) { return Color(0.5f + 0.5f * d.x, 0.5f + 0.5f * d.y, 1.0f); };
  const CubeMap cube(bakedCube(32, sky));
  Pcg32 rng(4, 4);
  float worst = 0.0f;
  for (int i = 0; i < 400; ++i) {
    // A point on one of the cube's twelve edges: two coordinates ±1, the third anywhere.
    const int axis = static_cast<int>(rng.nextFloat() * 3.0f) % 3;
    Vec3 edge(rng.nextFloat() < 0.5f ? -1.0f : 1.0f, rng.nextFloat() < 0.5f ? -1.0f : 1.0f, 0.0f);
    edge = axis == 0   ? Vec3(1.6f * rng.nextFloat() - 0.8f, edge.x, edge.y)
           : axis == 1 ? Vec3(edge.x, 1.6f * rng.nextFloat() - 0.8f, edge.y)
                       : Vec3(edge.x, edge.y, 1.6f * rng.nextFloat() - 0.8f);
    // Nudged off the edge onto one face, then onto the other.
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    Vec3 first = edge, second = edge;
    first[a] *= 0.999f;
    second[b] *= 0.999f;
    first = glm::normalize(first);
    second = glm::normalize(second);
    ASSERT_NE(cube.facePoint(first)->face, cube.facePoint(second)->face);
    for (const float angle : {0.0f, 0.05f, 0.2f, 0.8f}) {
      const Steps steps = stepsAcross(first, angle);
      const Color one = cube.lookup(first, steps.dx, steps.dy);
      const Color two = cube.lookup(second, steps.dx, steps.dy);
      worst = std::max(worst, maxComponent(glm::abs(one - two)));
    }
  }
  EXPECT_LT(worst, 0.05f);  // 0.032 measured; 0.40 with blends clamped to each face
}

// A ray cone of spread α reads, at a face's centre, what a differential stepping α per pixel
// reads; towards a face's corner the gnomonic stretch (1/ma² of a unit direction) widens it.
TEST(CubeMap, AConesSpreadReadsTheLevelOfTheSameDifferentialAtAFacesCentre) {
  CubeMapDesc d;
  for (int f = 0; f < 6; ++f) {
    d.faces[f] = ImageRgb(64, 64);
    for (int y = 0; y < 64; ++y) {
      for (int x = 0; x < 64; ++x) d.faces[f].at(x, y) = Color(static_cast<float>((x + y) % 2));
    }
  }
  const CubeMap cube(d);
  for (const float spread : {0.01f, 0.05f, 0.2f}) {
    const Vec3 centre(0.0f, 0.0f, -1.0f);
    const Color cone = cube.lookup(centre, spread);
    const Color differential = cube.lookup(centre, Vec3(spread, 0, 0), Vec3(0, spread, 0));
    EXPECT_NEAR(cone.x, differential.x, 1e-6f) << spread;
  }
  const Vec3 off = glm::normalize(Vec3(0.3f, 0.2f, -1.0f));
  EXPECT_EQ(cube.lookup(off, 0.0f), cube.lookup(off));  // no spread: the finest level
}

}  // namespace
}  // namespace prism
