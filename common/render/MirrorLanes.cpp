#include "render/MirrorLanes.h"

#include <limits>

namespace prism {

using namespace lanes;

void mirrorRayLanes(const ShadingLanes& s, Ray* rays) {
  const V noEnd = simd::broadcast<V>(std::numeric_limits<float>::infinity());
  for (int first = 0; first < ShadingLanes::kLanes; first += kWidth) {
    const Vec3Lanes geometric = load3(s.geometricNormal, first);
    const Vec3Lanes shading = load3(s.shadingNormal, first);
    const Vec3Lanes toViewer = load3(s.toViewer, first);
    Vec3Lanes incoming, aboutShading, aboutGeometric, direction;
    for (int a = 0; a < 3; ++a) incoming.x[a] = -toViewer.x[a];
    // reflect(d, n) = d - 2·(d·n)·n (shading/Optics.h), about either normal.
    const V twiceShading = 2.0f * dot(incoming, shading);
    const V twiceGeometric = 2.0f * dot(incoming, geometric);
    for (int a = 0; a < 3; ++a) {
      aboutShading.x[a] = incoming.x[a] - twiceShading * shading.x[a];
      aboutGeometric.x[a] = incoming.x[a] - twiceGeometric * geometric.x[a];
    }
    const M aboveSurface = dot(aboutShading, geometric) > 0.0f;
    for (int a = 0; a < 3; ++a) {
      direction.x[a] = simd::select<V>(aboveSurface, aboutShading.x[a], aboutGeometric.x[a]);
    }
    // leavingOrigin (math/RayOffset.h): leavingDistance along the normal, to the side it goes.
    const V leaving = simd::load<V>(s.leavingDistance + first);
    const V step = simd::select<V>(dot(direction, geometric) < 0.0f, -leaving, leaving);
    const Vec3Lanes position = load3(s.position, first);
    Vec3Lanes origin;
    for (int a = 0; a < 3; ++a) origin.x[a] = position.x[a] + step * geometric.x[a];
    storeRays(origin, direction, noEnd, rays + first);
  }
}

}  // namespace prism
