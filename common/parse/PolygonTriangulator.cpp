#include "parse/PolygonTriangulator.h"

#include <cmath>

namespace prism {

namespace {

// Work in double: the inputs are float, so products of coordinate differences are exact enough
// that the orientation tests below only fail for vertices that really are (nearly) collinear.
struct Point2 {
  double x = 0.0;
  double y = 0.0;
};

double cross(const Point2& o, const Point2& a, const Point2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

double distance(const Point2& a, const Point2& b) {
  return std::hypot(b.x - a.x, b.y - a.y);
}

bool samePoint(const Point2& a, const Point2& b) {
  return a.x == b.x && a.y == b.y;
}

// A turn whose sine is below this (about float precision) is treated as straight: its vertex is
// collinear with its neighbours, so cutting an ear there would make a sliver triangle.
constexpr double kStraightSine = 1e-7;

// Projects the polygon on the coordinate plane most parallel to it, mirrored where needed so that
// the polygon winds counter-clockwise in 2D when it does about its Newell normal.
std::vector<Point2> projectToPlane(std::span<const Vec3> polygon, const Vec3& normal) {
  const Vec3 a = glm::abs(normal);
  const int drop = (a.x >= a.y && a.x >= a.z) ? 0 : (a.y >= a.z ? 1 : 2);
  const int u = (drop + 1) % 3;
  const int v = (drop + 2) % 3;
  // With (u, v) taken cyclically after the dropped axis, the 2D signed area has the sign of
  // normal[drop].
  const double mirror = normal[drop] < 0.0f ? -1.0 : 1.0;
  std::vector<Point2> points(polygon.size());
  for (size_t i = 0; i < polygon.size(); ++i) {
    points[i] = {polygon[i][u], mirror * polygon[i][v]};
  }
  return points;
}

// The polygon's remaining vertices as a circular doubly linked list over the original indices.
class EarClipper {
 public:
  explicit EarClipper(std::vector<Point2> points) : points_(std::move(points)) {
    const size_t n = points_.size();
    prev_.resize(n);
    next_.resize(n);
    for (size_t i = 0; i < n; ++i) {
      prev_[i] = static_cast<uint32_t>((i + n - 1) % n);
      next_[i] = static_cast<uint32_t>((i + 1) % n);
    }
    remaining_ = n;
  }

  std::vector<uint32_t> run() {
    std::vector<uint32_t> triangles;
    uint32_t current = removeSpikes();
    size_t stepsWithoutCut = 0;
    while (remaining_ > 3) {
      if (stepsWithoutCut > remaining_) {
        // A full lap found no clean ear (rounding, or a self-intersecting polygon): clip the most
        // convex vertex anyway so the loop always ends.
        current = mostConvexVertex(current);
        if (turnSine(current) > kStraightSine) emit(current, triangles);
        current = remove(current);
        stepsWithoutCut = 0;
        continue;
      }
      const double sine = turnSine(current);
      if (isSpike(current, sine)) {
        // A repeated vertex, or an edge that doubles back on itself: drop it without a triangle,
        // then recheck its predecessor, whose turn has changed.
        current = prev_[remove(current)];
        stepsWithoutCut = 0;
      } else if (sine > kStraightSine && isEar(current)) {
        emit(current, triangles);
        current = remove(current);
        stepsWithoutCut = 0;
      } else {
        current = next_[current];
        ++stepsWithoutCut;
      }
    }
    if (remaining_ == 3 && turnSine(current) > kStraightSine) emit(current, triangles);
    return triangles;
  }

 private:
  // Drops every spike before clipping starts: an ear cut next to a spike could cover the spike's
  // outside. Returns a vertex that is left.
  uint32_t removeSpikes() {
    uint32_t i = 0;
    size_t checked = 0;  // consecutive vertices found not to be spikes
    while (remaining_ > 2 && checked < remaining_) {
      if (isSpike(i, turnSine(i))) {
        i = prev_[remove(i)];
        checked = 0;
      } else {
        i = next_[i];
        ++checked;
      }
    }
    return i;
  }

  // Sine of the turn at vertex i (positive: convex, in counter-clockwise order); 0 when i
  // coincides with a neighbour.
  double turnSine(uint32_t i) const {
    const Point2& a = points_[prev_[i]];
    const Point2& b = points_[i];
    const Point2& c = points_[next_[i]];
    const double lengths = distance(a, b) * distance(b, c);
    if (!(lengths > 0.0)) return 0.0;
    return cross(a, b, c) / lengths;
  }

  // A vertex that adds nothing but a zero-area triangle: one at the same place as a neighbour, or
  // one where the outline turns straight back. A vertex where the outline goes straight on is
  // kept (it is no ear, but a later ear uses it), so it does not become a T-junction.
  bool isSpike(uint32_t i, double sine) const {
    if (std::fabs(sine) > kStraightSine) return false;
    const Point2& a = points_[prev_[i]];
    const Point2& b = points_[i];
    const Point2& c = points_[next_[i]];
    return (b.x - a.x) * (c.x - b.x) + (b.y - a.y) * (c.y - b.y) <= 0.0;
  }

  // No other remaining vertex lies inside or on the triangle (prev, i, next). Vertices at the
  // same place as one of its corners (where a polygon touches itself) do not count.
  bool isEar(uint32_t i) const {
    const Point2& a = points_[prev_[i]];
    const Point2& b = points_[i];
    const Point2& c = points_[next_[i]];
    for (uint32_t j = next_[next_[i]]; j != prev_[i]; j = next_[j]) {
      const Point2& p = points_[j];
      if (samePoint(p, a) || samePoint(p, b) || samePoint(p, c)) continue;
      if (cross(a, b, p) >= 0.0 && cross(b, c, p) >= 0.0 && cross(c, a, p) >= 0.0) return false;
    }
    return true;
  }

  uint32_t mostConvexVertex(uint32_t start) const {
    uint32_t best = start;
    double bestSine = -2.0;
    uint32_t i = start;
    for (size_t k = 0; k < remaining_; ++k, i = next_[i]) {
      const double sine = turnSine(i);
      if (sine > bestSine) {
        bestSine = sine;
        best = i;
      }
    }
    return best;
  }

  void emit(uint32_t i, std::vector<uint32_t>& triangles) const {
    triangles.insert(triangles.end(), {prev_[i], i, next_[i]});
  }

  // Unlinks vertex i and returns its successor.
  uint32_t remove(uint32_t i) {
    next_[prev_[i]] = next_[i];
    prev_[next_[i]] = prev_[i];
    --remaining_;
    return next_[i];
  }

  std::vector<Point2> points_;
  std::vector<uint32_t> prev_;
  std::vector<uint32_t> next_;
  size_t remaining_ = 0;
};

}  // namespace

Vec3 newellNormal(std::span<const Vec3> polygon) {
  // Newell's method: sum over edges of the cross products' components, in double for the
  // cancellation in large, nearly planar polygons.
  double nx = 0.0, ny = 0.0, nz = 0.0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Vec3& a = polygon[i];
    const Vec3& b = polygon[(i + 1) % polygon.size()];
    nx += (double(a.y) - b.y) * (double(a.z) + b.z);
    ny += (double(a.z) - b.z) * (double(a.x) + b.x);
    nz += (double(a.x) - b.x) * (double(a.y) + b.y);
  }
  return Vec3(static_cast<float>(nx), static_cast<float>(ny), static_cast<float>(nz));
}

std::vector<uint32_t> triangulatePolygon(std::span<const Vec3> polygon) {
  if (polygon.size() < 3) return {};
  const Vec3 normal = newellNormal(polygon);
  if (!isFinite(normal) || maxAbsComponent(normal) == 0.0f) return {};
  return EarClipper(projectToPlane(polygon, normal)).run();
}

}  // namespace prism
