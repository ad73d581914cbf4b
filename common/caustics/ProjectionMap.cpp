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
  for (int row = 0; row < rows_; ++row) {
    for (int column = 0; column < columns_; ++column) {
      const Cell cell{1.0 - 2.0 * row / rows_, 1.0 - 2.0 * (row + 1) / rows_,
                      2.0 * kPiD * column / columns_, 2.0 * kPiD * (column + 1) / columns_};
      glm::dvec3 centre;
      double cellRadius;
      cellCone(cell, centre, cellRadius);
      bool marked = false;
      for (const CasterBounds& caster : casters) {
        if (caster.plane) {
          // The plane is reachable along directions pointing from the light towards it.
          const double side =
              static_cast<double>(caster.offset) - glm::dot(glm::dvec3(caster.normal), origin);
          if (side == 0.0) continue;  // the light lies on the plane
          const glm::dvec3 towards = glm::dvec3(caster.normal) * (side > 0.0 ? 1.0 : -1.0);
          marked = angleBetween(centre, towards) <= 0.5 * kPiD + cellRadius;
        } else {
          const glm::dvec3 toCentre = glm::dvec3(caster.center) - origin;
          const double distance = glm::length(toCentre);
          if (distance <= caster.radius) {
            marked = true;  // the light is inside the bounds: every direction may hit
          } else {
            const double angularRadius = std::asin(caster.radius / distance);
            marked = angleBetween(centre, toCentre / distance) <= angularRadius + cellRadius;
          }
        }
        if (marked) break;
      }
      if (marked) covered_.push_back(static_cast<uint32_t>(row * columns_ + column));
    }
  }
}

double ProjectionMap::coveredSolidAngle() const {
  return 4.0 * kPiD * static_cast<double>(covered_.size()) / static_cast<double>(cellCount());
}

Vec3 ProjectionMap::sample(float u0, float u1, float u2) const {
  const size_t n = covered_.size();
  const size_t pick = std::min(static_cast<size_t>(static_cast<double>(u0) * n), n - 1);
  const uint32_t cell = covered_[pick];
  const int row = static_cast<int>(cell / static_cast<uint32_t>(columns_));
  const int column = static_cast<int>(cell % static_cast<uint32_t>(columns_));
  const double z0 = 1.0 - 2.0 * row / rows_, z1 = 1.0 - 2.0 * (row + 1) / rows_;
  const double z = z0 + (z1 - z0) * u1;
  const double phi = 2.0 * kPiD * (column + static_cast<double>(u2)) / columns_;
  return Vec3(direction(z, phi));
}

}  // namespace prism
