#include "caustics/ProjectionMap.h"

#include <algorithm>
#include <cmath>

namespace prism {
namespace {

constexpr double kPiD = 3.14159265358979323846;

// Cell (row, column) spans z = cos θ in [zTop, zBottom] (z falls with the row) and
// φ in [φ0, φ1]. Directions are computed in double so narrow cells near the poles stay exact.
struct Cell {
  double z0, z1, phi0, phi1;
};

glm::dvec3 direction(double z, double phi) {
  const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {s * std::cos(phi), s * std::sin(phi), z};
}

double angleBetween(const glm::dvec3& a, const glm::dvec3& b) {
  return std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0));
}

// The cell's centre direction and the largest angle from it to the cell's corners and edge
// midpoints, widened by 5 % for the bulge of the latitude edges between those points.
void cellCone(const Cell& c, glm::dvec3& centre, double& radius) {
  const double zm = 0.5 * (c.z0 + c.z1), pm = 0.5 * (c.phi0 + c.phi1);
  centre = direction(zm, pm);
  radius = 0.0;
  for (double z : {c.z0, zm, c.z1}) {
    for (double phi : {c.phi0, pm, c.phi1}) {
      radius = std::max(radius, angleBetween(centre, direction(z, phi)));
    }
  }
  radius *= 1.05;
}

}  // namespace

ProjectionMap::ProjectionMap(const Vec3& light, const std::vector<CasterBounds>& casters, int rows)
    : rows_(std::max(rows, 1)), columns_(2 * std::max(rows, 1)) {
  const glm::dvec3 origin(light);
  const size_t cells = cellCount();
  std::vector<uint8_t> marked(cells, 0);
  // Each cell's cone, computed when a caster first needs it (nine acos each).
  std::vector<glm::dvec3> centres(cells);
  std::vector<double> radii(cells, -1.0);
  const auto cellAt = [&](int row, int column) {
    return Cell{1.0 - 2.0 * row / rows_, 1.0 - 2.0 * (row + 1) / rows_,
                2.0 * kPiD * column / columns_, 2.0 * kPiD * (column + 1) / columns_};
  };
  // Marks the cell if reaches(centre, cone radius) holds for it: each caster's test, cell by
  // cell, whichever cells it visits, so the marked set does not depend on the visiting.
  const auto markIf = [&](int row, int column, auto&& reaches) {
    const size_t k =
        static_cast<size_t>(row) * static_cast<size_t>(columns_) + static_cast<size_t>(column);
    if (marked[k]) return;
    if (radii[k] < 0.0) cellCone(cellAt(row, column), centres[k], radii[k]);
    if (reaches(centres[k], radii[k])) marked[k] = 1;
  };
  // The cones' largest radius: every cell of a row has the same shape, so the first column's
  // gives the row's, and 1 % more covers its rounding. It bounds where a caster can be seen.
  double widest = 0.0;
  for (int row = 0; row < rows_; ++row) {
    glm::dvec3 centre;
    double radius;
    cellCone(cellAt(row, 0), centre, radius);
    widest = std::max(widest, radius);
  }
  widest *= 1.01;

  // Testing every cell against every caster cost cells × casters (131 k × 7 382 bounding spheres
  // of balls-s4: a minute a light). A sphere is now tested only from the cells whose centres may
  // lie within its angular radius plus the widest cone, found by latitude and longitude with a
  // row and a column to spare; a plane still from every cell.
  for (const CasterBounds& caster : casters) {
    if (caster.plane) {
      // The plane is reachable along directions pointing from the light towards it.
      const double side =
          static_cast<double>(caster.offset) - glm::dot(glm::dvec3(caster.normal), origin);
      if (side == 0.0) continue;  // the light lies on the plane
      const glm::dvec3 towards = glm::dvec3(caster.normal) * (side > 0.0 ? 1.0 : -1.0);
      const auto facing = [&](const glm::dvec3& centre, double radius) {
        return angleBetween(centre, towards) <= 0.5 * kPiD + radius;
      };
      for (int row = 0; row < rows_; ++row) {
        for (int column = 0; column < columns_; ++column) markIf(row, column, facing);
      }
      continue;
    }
    const glm::dvec3 toCentre = glm::dvec3(caster.center) - origin;
    const double distance = glm::length(toCentre);
    if (distance <= caster.radius) {  // the light is inside the bounds: every direction may hit
      std::fill(marked.begin(), marked.end(), uint8_t{1});
      break;
    }
    if (!(distance > caster.radius)) continue;  // NaN bounds: nothing to aim at
    const glm::dvec3 axis = toCentre / distance;
    const double angularRadius = std::asin(caster.radius / distance);
    const auto seen = [&](const glm::dvec3& centre, double radius) {
      return angleBetween(centre, axis) <= angularRadius + radius;
    };
    const double reach = angularRadius + widest + 1e-9;
    const double polar = std::acos(std::clamp(axis.z, -1.0, 1.0));
    // Rows: z = cos θ of the centres within reach of the axis' polar angle.
    const double zHigh = std::cos(std::max(0.0, polar - reach));
    const double zLow = std::cos(std::min(kPiD, polar + reach));
    const int firstRow = std::max(0, static_cast<int>(std::floor((1.0 - zHigh) * 0.5 * rows_)) - 1);
    const int lastRow =
        std::min(rows_ - 1, static_cast<int>(std::floor((1.0 - zLow) * 0.5 * rows_)) + 1);
    // Columns: a cap clear of both poles spans asin(sin(reach) / sin θ) either side in φ.
    int firstColumn = 0, columnCount = columns_;
    if (polar - reach > 0.0 && polar + reach < kPiD) {
      const double spread = std::asin(std::min(1.0, std::sin(reach) / std::sin(polar)));
      double azimuth = std::atan2(axis.y, axis.x);
      if (azimuth < 0.0) azimuth += 2.0 * kPiD;
      const double perColumn = columns_ / (2.0 * kPiD);
      firstColumn = static_cast<int>(std::floor((azimuth - spread) * perColumn)) - 1;
      columnCount = std::min(
          columns_, static_cast<int>(std::floor((azimuth + spread) * perColumn)) + 2 - firstColumn);
    }
    for (int row = firstRow; row <= lastRow; ++row) {
      for (int i = 0; i < columnCount; ++i) {
        markIf(row, ((firstColumn + i) % columns_ + columns_) % columns_, seen);
      }
    }
  }
  for (size_t k = 0; k < cells; ++k) {
    if (marked[k]) covered_.push_back(static_cast<uint32_t>(k));
  }
}

double ProjectionMap::coveredSolidAngle() const {
  return 4.0 * kPiD * static_cast<double>(covered_.size()) / static_cast<double>(cellCount());
}

Vec3 ProjectionMap::sample(float u0, float u1, float u2) const {
  const size_t n = covered_.size();
  return sampleCell(std::min(static_cast<size_t>(static_cast<double>(u0) * n), n - 1), u1, u2);
}

Vec3 ProjectionMap::sampleCell(size_t pick, float u1, float u2) const {
  const uint32_t cell = covered_[pick];
  const int row = static_cast<int>(cell / static_cast<uint32_t>(columns_));
  const int column = static_cast<int>(cell % static_cast<uint32_t>(columns_));
  const double z0 = 1.0 - 2.0 * row / rows_, z1 = 1.0 - 2.0 * (row + 1) / rows_;
  const double z = z0 + (z1 - z0) * u1;
  const double phi = 2.0 * kPiD * (column + static_cast<double>(u2)) / columns_;
  return Vec3(direction(z, phi));
}

}  // namespace prism
