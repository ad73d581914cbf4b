#include "parse/PolygonTriangulator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

namespace prism {
namespace {

std::vector<Vec3> inPlaneZ0(const std::vector<Vec2>& points) {
  std::vector<Vec3> polygon;
  for (const Vec2& p : points) polygon.emplace_back(p.x, p.y, 0.0f);
  return polygon;
}

// Signed area by the shoelace formula (positive when counter-clockwise).
double shoelace(const std::vector<Vec2>& points) {
  double twice = 0.0;
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec2& a = points[i];
    const Vec2& b = points[(i + 1) % points.size()];
    twice += double(a.x) * b.y - double(b.x) * a.y;
  }
  return 0.5 * twice;
}

double triangleArea(const std::vector<Vec3>& polygon, const std::vector<uint32_t>& indices,
                    size_t t) {
  const glm::dvec3 a = polygon[indices[3 * t]];
  const glm::dvec3 b = polygon[indices[3 * t + 1]];
  const glm::dvec3 c = polygon[indices[3 * t + 2]];
  return 0.5 * glm::length(glm::cross(b - a, c - a));
}

double totalArea(const std::vector<Vec3>& polygon, const std::vector<uint32_t>& indices) {
  double area = 0.0;
  for (size_t t = 0; t < indices.size() / 3; ++t) area += triangleArea(polygon, indices, t);
  return area;
}

double cross2(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (double(a.x) - o.x) * (double(b.y) - o.y) - (double(a.y) - o.y) * (double(b.x) - o.x);
}

bool insidePolygon(const std::vector<Vec2>& points, const Vec2& p) {
  bool inside = false;
  for (size_t i = 0, j = points.size() - 1; i < points.size(); j = i++) {
    const Vec2& a = points[i];
    const Vec2& b = points[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) {
      inside = !inside;
    }
  }
  return inside;
}

// Segments ab and cd cross at a point inside both (touching at an end does not count).
bool properlyCross(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double d1 = cross2(a, b, c), d2 = cross2(a, b, d);
  const double d3 = cross2(c, d, a), d4 = cross2(c, d, b);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

// The full check for a simple polygon in the z = 0 plane: n - 2 triangles wound like the polygon,
// all inside it, whose areas add up to the polygon's.
void expectExactTriangulation(const std::vector<Vec2>& points) {
  const std::vector<Vec3> polygon = inPlaneZ0(points);
  const std::vector<uint32_t> indices = triangulatePolygon(polygon);
  ASSERT_EQ(indices.size(), 3 * (points.size() - 2));
  for (uint32_t index : indices) ASSERT_LT(index, points.size());
  const double area = std::fabs(shoelace(points));
  EXPECT_NEAR(totalArea(polygon, indices), area, 1e-9 * area + 1e-12);
  const float windingSign = shoelace(points) > 0.0 ? 1.0f : -1.0f;
  for (size_t t = 0; t < indices.size() / 3; ++t) {
    const Vec2& a = points[indices[3 * t]];
    const Vec2& b = points[indices[3 * t + 1]];
    const Vec2& c = points[indices[3 * t + 2]];
    EXPECT_GT(windingSign * cross2(a, b, c), 0.0) << "triangle " << t << " is flipped or flat";
    EXPECT_TRUE(insidePolygon(points, (a + b + c) / 3.0f)) << "triangle " << t << " is outside";
    for (size_t i = 0; i < points.size(); ++i) {
      const Vec2& p = points[i];
      const Vec2& q = points[(i + 1) % points.size()];
      EXPECT_FALSE(properlyCross(a, b, p, q) || properlyCross(b, c, p, q) ||
                   properlyCross(c, a, p, q))
          << "triangle " << t << " crosses edge " << i;
    }
  }
}

std::vector<Vec2> star(int points, float outer, float inner) {
  std::vector<Vec2> star;
  for (int i = 0; i < 2 * points; ++i) {
    const float angle = kPi * i / points;
    const float r = i % 2 == 0 ? outer : inner;
    star.emplace_back(r * std::cos(angle), r * std::sin(angle));
  }
  return star;
}

TEST(PolygonTriangulator, TriangleStaysAsIs) {
  const std::vector<Vec3> triangle = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<uint32_t> indices = triangulatePolygon(triangle);
  ASSERT_EQ(indices.size(), 3u);
  // Any rotation of 0 1 2 keeps the winding.
  EXPECT_EQ((indices[0] + 1) % 3, indices[1]);
  EXPECT_EQ((indices[1] + 1) % 3, indices[2]);
}

TEST(PolygonTriangulator, LShape) {
  expectExactTriangulation({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}});
}

TEST(PolygonTriangulator, FivePointedStar) {
  expectExactTriangulation(star(5, 1.0f, 0.4f));
}

TEST(PolygonTriangulator, ClockwiseStar) {
  std::vector<Vec2> clockwise = star(7, 2.0f, 0.5f);
  std::reverse(clockwise.begin(), clockwise.end());
  expectExactTriangulation(clockwise);
}

TEST(PolygonTriangulator, CombWithManyReflexVertices) {
  // A bar with four rectangular notches cut into its top edge.
  std::vector<Vec2> comb = {{0, 0}, {10, 0}, {10, 3}};
  for (int k = 4; k >= 1; --k) {
    const float x = 2.0f * k;
    comb.insert(comb.end(), {{x + 0.5f, 3}, {x + 0.5f, 1}, {x - 0.5f, 1}, {x - 0.5f, 3}});
  }
  comb.emplace_back(0, 3);
  expectExactTriangulation(comb);
}

TEST(PolygonTriangulator, SpiralTouchingNothing) {
  std::vector<Vec2> outer, inner;
  for (int i = 0; i <= 60; ++i) {
    const float angle = 0.2f * i;
    const float r = 1.0f + 0.15f * angle;
    outer.emplace_back(r * std::cos(angle), r * std::sin(angle));
    inner.emplace_back(0.8f * r * std::cos(angle), 0.8f * r * std::sin(angle));
  }
  std::vector<Vec2> spiral = outer;
  spiral.insert(spiral.end(), inner.rbegin(), inner.rend());
  expectExactTriangulation(spiral);
}

TEST(PolygonTriangulator, LargeConvexPolygon) {
  std::vector<Vec2> circle;
  for (int i = 0; i < 1000; ++i) {
    const float angle = 2.0f * kPi * i / 1000;
    circle.emplace_back(std::cos(angle), std::sin(angle));
  }
  const std::vector<Vec3> polygon = inPlaneZ0(circle);
  const std::vector<uint32_t> indices = triangulatePolygon(polygon);
  EXPECT_EQ(indices.size(), 3u * 998);
  EXPECT_NEAR(totalArea(polygon, indices), shoelace(circle), 1e-6);
}

TEST(PolygonTriangulator, TiltedStarInSpace) {
  // A star in a tilted plane, away from the origin: projection must not change the area.
  const std::vector<Vec2> flat = star(6, 1.5f, 0.6f);
  const Vec3 u = glm::normalize(Vec3(1, 2, 0.5f));
  const Vec3 v = glm::normalize(glm::cross(Vec3(0.3f, -0.2f, 1), u));
  const Vec3 origin(5, -3, 2);
  std::vector<Vec3> polygon;
  for (const Vec2& p : flat) polygon.push_back(origin + p.x * u + p.y * v);
  const std::vector<uint32_t> indices = triangulatePolygon(polygon);
  ASSERT_EQ(indices.size(), 3 * (flat.size() - 2));
  EXPECT_NEAR(totalArea(polygon, indices), shoelace(flat), 1e-5);
  const Vec3 normal = glm::normalize(newellNormal(polygon));
  EXPECT_NEAR(glm::dot(normal, glm::normalize(glm::cross(u, v))), 1.0f, 1e-5f);
  for (size_t t = 0; t < indices.size() / 3; ++t) {
    const Vec3& a = polygon[indices[3 * t]];
    const Vec3& b = polygon[indices[3 * t + 1]];
    const Vec3& c = polygon[indices[3 * t + 2]];
    EXPECT_GT(glm::dot(glm::cross(b - a, c - a), normal), 0.0f) << "triangle " << t;
  }
}

TEST(PolygonTriangulator, NewellNormalIsTwiceTheArea) {
  const std::vector<Vec2> l = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  const Vec3 normal = newellNormal(inPlaneZ0(l));
  EXPECT_FLOAT_EQ(normal.z, 6.0f);
  EXPECT_FLOAT_EQ(normal.x, 0.0f);
  EXPECT_FLOAT_EQ(normal.y, 0.0f);
}

TEST(PolygonTriangulator, CollinearVerticesAreKeptWithoutSlivers) {
  // A unit square with a vertex in the middle of every edge: no T-junction may appear.
  expectExactTriangulation(
      {{0, 0}, {0.5f, 0}, {1, 0}, {1, 0.5f}, {1, 1}, {0.5f, 1}, {0, 1}, {0, 0.5f}});
  // Two straight vertices in a row, and a vertex that becomes straight once an ear is cut.
  expectExactTriangulation({{0, 0}, {1, 0}, {2, 0}, {3, 0}, {3, 1}, {0, 1}});
  expectExactTriangulation({{0, 0}, {2, 0}, {2, 2}, {1, 1}, {0, 2}});
}

TEST(PolygonTriangulator, EdgeDoublingBackIsDropped) {
  // A square with a zero-width spike: (1, 0.5) -> (1, 0.8) -> back to (1, 0.5).
  const std::vector<Vec3> polygon =
      inPlaneZ0({{0, 0}, {1, 0}, {1, 0.5f}, {1.5f, 0.5f}, {1, 0.5f}, {1, 1}, {0, 1}});
  const std::vector<uint32_t> indices = triangulatePolygon(polygon);
  EXPECT_NEAR(totalArea(polygon, indices), 1.0, 1e-12);
  for (size_t t = 0; t < indices.size() / 3; ++t) {
    EXPECT_GT(triangleArea(polygon, indices, t), 1e-3) << "flat triangle " << t;
  }
}

TEST(PolygonTriangulator, DuplicateVerticesAreDropped) {
  const std::vector<Vec3> polygon =
      inPlaneZ0({{0, 0}, {0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 1}, {1, 2}, {0, 2}, {0, 0}});
  const std::vector<uint32_t> indices = triangulatePolygon(polygon);
  EXPECT_EQ(indices.size(), 3u * 4);
  EXPECT_NEAR(totalArea(polygon, indices), 3.0, 1e-12);
}

TEST(PolygonTriangulator, PolygonsWithoutAreaGiveNothing) {
  EXPECT_TRUE(triangulatePolygon(inPlaneZ0({{0, 0}, {1, 1}, {2, 2}, {3, 3}})).empty());
  EXPECT_TRUE(triangulatePolygon(inPlaneZ0({{1, 1}, {1, 1}, {1, 1}})).empty());
  EXPECT_TRUE(triangulatePolygon(inPlaneZ0({{0, 0}, {1, 0}})).empty());
  EXPECT_TRUE(triangulatePolygon(std::vector<Vec3>{}).empty());
  const float nan = std::nanf("");
  EXPECT_TRUE(triangulatePolygon(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {nan, 1, 0}}).empty());
}

TEST(PolygonTriangulator, SelfIntersectingInputsTerminate) {
  // A bow tie, then random polygons: not simple, so only termination and valid indices count.
  const std::vector<Vec3> bowTie = inPlaneZ0({{0, 0}, {1, 1}, {1, 0}, {0, 1}});
  const std::vector<uint32_t> indices = triangulatePolygon(bowTie);
  EXPECT_LE(indices.size(), 3u * 2);
  std::mt19937 random(7);
  std::uniform_real_distribution<float> coordinate(-1.0f, 1.0f);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<Vec3> polygon(3 + trial % 40);
    for (Vec3& p : polygon) {
      const float x = coordinate(random);
      p = Vec3(x, coordinate(random), 0.01f * x);  // slightly off the z = 0 plane
    }
    const std::vector<uint32_t> result = triangulatePolygon(polygon);
    ASSERT_EQ(result.size() % 3, 0u);
    ASSERT_LE(result.size(), 3 * (polygon.size() - 2));
    for (uint32_t index : result) ASSERT_LT(index, polygon.size());
  }
}

// The first concave 144-gon of the SPD gears scene (a gear's outline at z = 1).
TEST(PolygonTriangulator, SpdGearOutline) {
  std::ifstream in(PRISM_TEST_DATA_DIR "/nff/gears-s2.nff");
  ASSERT_TRUE(in);
  std::string line;
  while (std::getline(in, line) && line != "p 144") {
  }
  ASSERT_EQ(line, "p 144");
  std::vector<Vec2> gear(144);
  for (Vec2& p : gear) {
    float z = 0.0f;
    in >> p.x >> p.y >> z;
    ASSERT_FLOAT_EQ(z, 1.0f);
  }
  EXPECT_GT(shoelace(gear), 0.0);  // counter-clockwise seen from +z: the face looks up
  expectExactTriangulation(gear);
}

}  // namespace
}  // namespace prism
