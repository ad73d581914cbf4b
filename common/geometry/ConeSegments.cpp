#include "geometry/ConeSegments.h"

namespace prism {
namespace {

// Cutting stops when halving the parts again would keep more than this share of their boxes'
// total surface area: each part is one more BVH entry to walk past.
constexpr float kWorthwhileShrink = 0.85f;
constexpr int kMaxSegments = 16;

// Part i of n equal parts; the outer ends are the cone's own, exactly.
Cone part(const Cone& cone, int i, int n) {
  const float h = cone.height();
  const float zLow = i == 0 ? 0.0f : h * static_cast<float>(i) / static_cast<float>(n);
  const float zHigh = i + 1 == n ? h : h * static_cast<float>(i + 1) / static_cast<float>(n);
  return cone.segment(zLow, zHigh);
}

float totalSurfaceArea(const Cone& cone, int n) {
  float area = 0.0f;
  for (int i = 0; i < n; ++i) area += part(cone, i, n).bounds().surfaceArea();
  return area;
}

}  // namespace

int bvhPartCount(const Cone& cone) {
  int segments = 1;
  float area = cone.bounds().surfaceArea();
  while (segments < kMaxSegments) {
    const float halvedArea = totalSurfaceArea(cone, 2 * segments);
    if (!(halvedArea < kWorthwhileShrink * area)) break;
    segments *= 2;
    area = halvedArea;
  }
  return segments;
}

std::vector<Cone> bvhParts(const Cone& cone) {
  const int segments = bvhPartCount(cone);
  std::vector<Cone> parts;
  parts.reserve(segments);
  for (int i = 0; i < segments; ++i) parts.push_back(part(cone, i, segments));
  return parts;
}

}  // namespace prism
