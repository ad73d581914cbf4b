// One ray at a time: the closest-hit and the any-hit walk (compiled once per instruction set;
// accel/IsaVariant.h).
#include "accel/LeafTests.h"
#include "accel/SceneGeometry.h"

namespace prism {

bool SceneGeometry::blockedByPlane(const Ray& ray) const {
  float t;
  for (const Plane& plane : planes_) {
    if (plane.intersect(ray, ray.tMax, t)) return true;
  }
  return false;
}

template <bool kAnyHit>
bool SceneGeometry::intersectBounded(const Ray& ray, float& tMax, HitRecord& hit) const {
  const WatertightRay sheared = shearFor(ray);  // once per ray, not per triangle
  if (traversal_ == Traversal::BinaryScalar) {
    return bvh_.traverse(ray, tMax, kAnyHit, [&](uint32_t first, uint32_t count, float& leafTMax) {
      return intersectLeaf<kAnyHit>(ray, sheared, first, count, false, leafTMax, hit);
    });
  }
  if (!packed_) {
    return wideBvh_.traverse<kAnyHit>(ray, tMax, [&](uint32_t first, uint32_t count, float& t) {
      return intersectLeaf<kAnyHit>(ray, sheared, first, count, false, t, hit);
    });
  }
  return wideBvh_.traverse<kAnyHit>(ray, tMax, [&](uint32_t first, uint32_t count, float& t) {
    return intersectLeafPacked<kAnyHit>(ray, sheared, first, count, t, hit);
  });
}

bool SceneGeometry::Kernels::intersect(const SceneGeometry& g, const Ray& ray, HitRecord& hit) {
  float tMax = ray.tMax;
  bool found = g.intersectBounded<false>(ray, tMax, hit);
  for (uint32_t i = 0; i < g.planes_.size(); ++i) {
    float t;
    if (g.planes_[i].intersect(ray, tMax, t)) {
      tMax = t;
      hit = {t, PrimitiveRef::make(PrimitiveKind::Plane, i), 0.0f, 0.0f};
      found = true;
    }
  }
  return found;
}

bool SceneGeometry::Kernels::occluded(const SceneGeometry& g, const Ray& ray) {
  if (g.blockedByPlane(ray)) return true;
  // A shadow ray from a plane (nearly the only ones that start outside the tree's box, which
  // holds every bounded surface) often misses the whole tree: found without the walk's set-up
  // and root test. Half of the default scene's lone shadow rays; without planes it only costs.
  if (g.testTreeBoxFirst_ && !g.wideBvh_.entersTree(ray, ray.tMax)) return false;
  float tMax = ray.tMax;
  HitRecord ignored;
  return g.intersectBounded<true>(ray, tMax, ignored);
}

}  // namespace prism
