#include "caustics/ProjectionMap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

namespace prism {
namespace {

constexpr double kPiD = 3.14159265358979323846;
constexpr int kRows = ProjectionMap::kDefaultRows;
constexpr int kColumns = 2 * kRows;

CasterBounds sphereBounds(const Vec3& centre, float radius) {
  CasterBounds c;
  c.center = centre;
  c.radius = radius;
  return c;
}

CasterBounds planeBounds(const Vec3& normal, float offset) {
  CasterBounds c;
  c.plane = true;
  c.normal = normal;
  c.offset = offset;
  return c;
}

double capSolidAngle(double halfAngle) {
  return 2.0 * kPiD * (1.0 - std::cos(halfAngle));
}

// The map's cells: rows uniform in z = cos θ from +1 down to -1, columns uniform in φ.
std::pair<int, int> cellOf(double z, double phi) {
  if (phi < 0.0) phi += 2.0 * kPiD;
  const int row = std::clamp(static_cast<int>((1.0 - z) * 0.5 * kRows), 0, kRows - 1);
  const int column = std::clamp(static_cast<int>(phi / (2.0 * kPiD) * kColumns), 0, kColumns - 1);
  return {row, column};
}

// The marked cells, read back through sample(): u0 = (i + ½)/n picks marked cell i, and
// u1 = u2 = ½ its centre.
std::set<std::pair<int, int>> markedCells(const ProjectionMap& map) {
  std::set<std::pair<int, int>> cells;
  const size_t n = map.coveredCellCount();
  for (size_t i = 0; i < n; ++i) {
    const Vec3 d = map.sample(static_cast<float>((i + 0.5) / static_cast<double>(n)), 0.5f, 0.5f);
    cells.insert(cellOf(d.z, std::atan2(d.y, d.x)));
  }
  return cells;
}

// Whether d lies in a marked cell. A direction within 1e-5 of a cell edge (float rounding of
// the sampled direction) may land in either neighbour; both are accepted then.
bool inMarkedCell(const std::set<std::pair<int, int>>& cells, const Vec3& d) {
  const double z = d.z, phi = std::atan2(d.y, d.x);
  for (double dz : {0.0, -1e-5, 1e-5}) {
    for (double dphi : {0.0, -1e-5, 1e-5}) {
      if (cells.count(cellOf(z + dz, phi + dphi))) return true;
    }
  }
  return false;
}

// A uniformly random direction within halfAngle of axis.
Vec3 directionInCone(const Vec3& axis, double halfAngle, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double z = 1.0 - u(rng) * (1.0 - std::cos(halfAngle));
  const double phi = 2.0 * kPiD * u(rng);
  const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
  const glm::dvec3 w = glm::normalize(glm::dvec3(axis));
  const glm::dvec3 a = std::abs(w.x) > 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
  const glm::dvec3 uAxis = glm::normalize(glm::cross(a, w));
  const glm::dvec3 vAxis = glm::cross(w, uAxis);
  return Vec3(s * std::cos(phi) * uAxis + s * std::sin(phi) * vAxis + z * w);
}

bool hitsSphere(const Vec3& origin, const Vec3& direction, const Vec3& centre, float radius) {
  const glm::dvec3 oc = glm::dvec3(centre) - glm::dvec3(origin);
  const double along = glm::dot(oc, glm::dvec3(direction));
  return along > 0.0 && glm::dot(oc, oc) - along * along <= double(radius) * radius;
}

// A sphere of radius 1 at distance 5 from the light: angular radius β = asin(1/5), seen along
// several axes (the equator of the map, a pole where its cells are long and thin, in between).
class ProjectionMapSphere : public testing::TestWithParam<Vec3> {};

// Covered ≥ the exact cap 2π(1 − cos β): marking errs towards too many cells. And not wildly
// more: a cell is marked only when its centre lies within β + ρ of the sphere's centre, ρ its
// angular radius, so the marked cells lie within β + 2ρ. The largest cell radius ρ is ~0.125 rad
// (the polar row spans z from 1 to 1 − 2/256, θ up to acos(1 − 1/128) ≈ 0.125), so the bound
// is cap(β + 0.26) — looser than the measured ~1.2× near the equator, exact near the poles.
TEST_P(ProjectionMapSphere, CoversTheCapAndNotWildlyMore) {
  const Vec3 axis = glm::normalize(GetParam());
  const Vec3 light(0.5f, -1.0f, 2.0f);
  const double beta = std::asin(1.0 / 5.0);
  const ProjectionMap map(light, {sphereBounds(light + 5.0f * axis, 1.0f)});
  EXPECT_EQ(map.cellCount(), size_t(kRows) * kColumns);
  const double covered = map.coveredSolidAngle();
  EXPECT_GE(covered, capSolidAngle(beta));
  EXPECT_LE(covered, capSolidAngle(beta + 0.26));
  // Near the equator cells are ~0.0077 rad in radius: the tighter bound cap(β + 2·0.0077·1.05).
  if (std::abs(axis.z) < 0.5f) {
    EXPECT_LE(covered, capSolidAngle(beta + 0.017));
  }
  RecordProperty("covered_over_cap", std::to_string(covered / capSolidAngle(beta)));
}

// Every direction that reaches the sphere leaves through a marked cell (no light is lost), and
// every sampled direction lies in a marked cell.
TEST_P(ProjectionMapSphere, MarkedCellsContainEveryDirectionToTheSphereAndEverySample) {
  const Vec3 axis = glm::normalize(GetParam());
  const Vec3 light(0.0f);
  const double beta = std::asin(1.0 / 5.0);
  const ProjectionMap map(light, {sphereBounds(5.0f * axis, 1.0f)});
  const auto cells = markedCells(map);
  ASSERT_EQ(cells.size(), map.coveredCellCount());  // the read-back found distinct cells
  std::mt19937 rng(11);
  for (int i = 0; i < 20000; ++i) {
    const Vec3 d = directionInCone(axis, beta * 0.99999, rng);
    ASSERT_TRUE(inMarkedCell(cells, d))
        << "direction to the sphere in an unmarked cell: " << d.x << " " << d.y << " " << d.z;
  }
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 20000; ++i) {
    const Vec3 d = map.sample(u(rng), u(rng), u(rng));
    EXPECT_NEAR(glm::length(d), 1.0f, 1e-6f);
    ASSERT_TRUE(inMarkedCell(cells, d)) << d.x << " " << d.y << " " << d.z;
  }
}

// Samples are uniform over the marked solid angle, so the fraction that hits the sphere is
// cap / covered. Binomial: σ = √(p(1−p)/N) ≤ 0.5/√N = 0.0011 for N = 2·10⁵; 5σ = 0.0056.
TEST_P(ProjectionMapSphere, FractionOfSamplesHittingTheSphereIsCapOverCovered) {
  const Vec3 axis = glm::normalize(GetParam());
  const Vec3 light(1.0f, 2.0f, 3.0f);
  const Vec3 centre = light + 5.0f * axis;
  const ProjectionMap map(light, {sphereBounds(centre, 1.0f)});
  const double expected = capSolidAngle(std::asin(1.0 / 5.0)) / map.coveredSolidAngle();
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  constexpr int kSamples = 200000;
  int hits = 0;
  for (int i = 0; i < kSamples; ++i) {
    hits += hitsSphere(light, map.sample(u(rng), u(rng), u(rng)), centre, 1.0f);
  }
  EXPECT_NEAR(static_cast<double>(hits) / kSamples, expected, 0.0056);
}

INSTANTIATE_TEST_SUITE_P(Axes, ProjectionMapSphere,
                         testing::Values(Vec3(1, 0, 0), Vec3(0, -1, 0), Vec3(0, 0, 1),
                                         Vec3(0, 0, -1), Vec3(1, 2, -0.7f)));

TEST(ProjectionMap, LightInsideTheBoundsCoversTheWholeSphere) {
  const ProjectionMap map(Vec3(0.1f, 0.2f, 0.0f), {sphereBounds(Vec3(0.0f), 1.0f)});
  EXPECT_EQ(map.coveredCellCount(), map.cellCount());
  EXPECT_NEAR(map.coveredSolidAngle(), 4.0 * kPiD, 1e-12);
}

// A plane marks the half of the sphere of directions facing it, plus the cells that straddle
// its horizon: about 2π. The horizon band is at most 2ρ wide (ρ the cell radius, up to 0.125
// rad only at the two poles it crosses, ~0.008 elsewhere), so a few per cent at most.
TEST(ProjectionMap, PlaneCasterCoversAboutHalfTheSphere) {
  const Vec3 normals[] = {{0, 0, 1}, {0, 1, 0}, glm::normalize(Vec3(1, -1, 0.5f))};
  for (const Vec3& n : normals) {
    for (float offset : {-2.0f, 3.0f}) {  // the light at the origin, below or above the plane
      const ProjectionMap map(Vec3(0.0f), {planeBounds(n, offset)});
      EXPECT_GE(map.coveredSolidAngle(), 2.0 * kPiD);
      EXPECT_LE(map.coveredSolidAngle(), 2.0 * kPiD * 1.05);
      // The direction straight at the plane is marked; straight away from it is not.
      const Vec3 towards = offset > 0.0f ? n : -n;
      const auto cells = markedCells(map);
      EXPECT_TRUE(inMarkedCell(cells, towards));
      EXPECT_FALSE(inMarkedCell(cells, -towards));
    }
  }
  // With the plane through z = 0 seen along the map's own axis, the horizon band is exactly the
  // row just past the equator: 2π + 4π/256.
  const ProjectionMap map(Vec3(0, 0, 1), {planeBounds(Vec3(0, 0, 1), 0.0f)});
  EXPECT_NEAR(map.coveredSolidAngle(), 2.0 * kPiD + 4.0 * kPiD / kRows, 1e-9);
}

// The map's marking, cell by cell against every caster (the definition, at cells × casters
// cost), for checking that the map's faster search marks exactly the same cells.
std::set<std::pair<int, int>> everyCellAgainstEveryCaster(
    const Vec3& light, const std::vector<CasterBounds>& casters) {
  const auto direction = [](double z, double phi) {
    const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
    return glm::dvec3(s * std::cos(phi), s * std::sin(phi), z);
  };
  const auto angle = [](const glm::dvec3& a, const glm::dvec3& b) {
    return std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0));
  };
  const glm::dvec3 origin(light);
  std::set<std::pair<int, int>> cells;
  for (int row = 0; row < kRows; ++row) {
    for (int column = 0; column < kColumns; ++column) {
      const double z0 = 1.0 - 2.0 * row / kRows, z1 = 1.0 - 2.0 * (row + 1) / kRows;
      const double phi0 = 2.0 * kPiD * column / kColumns;
      const double phi1 = 2.0 * kPiD * (column + 1) / kColumns;
      const double zm = 0.5 * (z0 + z1), pm = 0.5 * (phi0 + phi1);
      const glm::dvec3 centre = direction(zm, pm);
      double radius = 0.0;
      for (double z : {z0, zm, z1}) {
        for (double phi : {phi0, pm, phi1}) {
          radius = std::max(radius, angle(centre, direction(z, phi)));
        }
      }
      radius *= 1.05;
      for (const CasterBounds& c : casters) {
        bool reaches = false;
        if (c.plane) {
          const double side = double(c.offset) - glm::dot(glm::dvec3(c.normal), origin);
          reaches = side != 0.0 && angle(centre, glm::dvec3(c.normal) * (side > 0 ? 1.0 : -1.0)) <=
                                       0.5 * kPiD + radius;
        } else {
          const glm::dvec3 toCentre = glm::dvec3(c.center) - origin;
          const double distance = glm::length(toCentre);
          reaches = distance <= c.radius ||
                    angle(centre, toCentre / distance) <= std::asin(c.radius / distance) + radius;
        }
        if (reaches) {
          cells.insert({row, column});
          break;
        }
      }
    }
  }
  return cells;
}

// The map finds each sphere's cells from its latitude and longitude instead of testing every
// cell: the same cells come out, for spheres small and large, near the poles, across φ = 0 and
// close to the light, with and without a plane among them.
TEST(ProjectionMap, MarksExactlyTheCellsThatTestingEveryCellMarks) {
  std::mt19937 rng(29);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const Vec3 light(0.3f, -0.2f, 1.0f);
  std::vector<CasterBounds> casters;
  for (int i = 0; i < 40; ++i) {
    const Vec3 axis = directionInCone(Vec3(0, 0, 1), kPiD, rng);  // anywhere on the sphere
    const float distance = 1.5f + 30.0f * u(rng) * u(rng);
    casters.push_back(sphereBounds(light + distance * axis, distance * (0.001f + 0.4f * u(rng))));
  }
  casters.push_back(sphereBounds(light + Vec3(0.0f, 0.0f, 7.0f), 0.05f));   // at a pole
  casters.push_back(sphereBounds(light + Vec3(0.0f, 0.0f, -3.0f), 0.5f));   // the other pole
  casters.push_back(sphereBounds(light + Vec3(5.0f, -0.01f, 0.0f), 0.2f));  // across φ = 0
  const auto sparse = std::vector<CasterBounds>(casters.begin(), casters.begin() + 12);
  for (const auto& set : {sparse, casters}) {
    const ProjectionMap map(light, set);
    const auto cells = markedCells(map);
    ASSERT_EQ(cells.size(), map.coveredCellCount());
    EXPECT_EQ(cells, everyCellAgainstEveryCaster(light, set));
    EXPECT_LT(map.coveredCellCount(), map.cellCount());
  }
  std::vector<CasterBounds> withPlane(sparse.begin(), sparse.begin() + 4);
  withPlane.push_back(planeBounds(glm::normalize(Vec3(0.2f, 1.0f, 0.1f)), -3.0f));
  const ProjectionMap map(light, withPlane);
  EXPECT_EQ(markedCells(map), everyCellAgainstEveryCaster(light, withPlane));
}

TEST(ProjectionMap, NoCastersMarksNothing) {
  const ProjectionMap map(Vec3(0.0f), {});
  EXPECT_TRUE(map.empty());
  EXPECT_EQ(map.coveredCellCount(), 0u);
  EXPECT_EQ(map.coveredSolidAngle(), 0.0);
}

TEST(ProjectionMap, LightOnACastingPlaneMarksNothingForIt) {
  const ProjectionMap map(Vec3(1, 2, 0), {planeBounds(Vec3(0, 0, 1), 0.0f)});
  EXPECT_TRUE(map.empty());
}

TEST(ProjectionMap, SeveralCastersMarkTheUnionOfTheirCaps) {
  const Vec3 light(0.0f);
  const CasterBounds a = sphereBounds({4, 0, 0}, 1.0f), b = sphereBounds({0, 0, -6}, 2.0f);
  const ProjectionMap both(light, {a, b}), onlyA(light, {a}), onlyB(light, {b});
  // The caps are far apart (90° between the axes): their cells are disjoint.
  EXPECT_EQ(both.coveredCellCount(), onlyA.coveredCellCount() + onlyB.coveredCellCount());
}

}  // namespace
}  // namespace prism
