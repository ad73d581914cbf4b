// The single-ray leaf tests of SceneGeometry's walks, shared by the single-ray and the packet
// walk (a packet's rays that cannot share a vector take them one by one). Included only by the
// kernel sources, which are compiled once per instruction set.
#pragma once

#include "accel/PrimitiveRef.h"
#include "accel/SceneGeometry.h"
#include "geometry/TriangleMollerTrumbore.h"
#include "geometry/TriangleMollerTrumbore4.h"
#include "geometry/TrianglePlaneInside.h"
#include "geometry/TriangleWatertight4.h"

namespace prism {

template <bool kAnyHit>
bool SceneGeometry::intersectLeaf(const Ray& ray, const WatertightRay& sheared, uint32_t first,
                                  uint32_t count, bool skipTriangles, float& tMax,
                                  HitRecord& hit) const {
  const TriangleTest test = triangleTest_;
  bool found = false;
  for (uint32_t i = first; i < first + count; ++i) {
    const uint32_t ref = leafRefs_[i];
    const uint32_t index = PrimitiveRef::index(ref);
    float t, u = 0.0f, v = 0.0f;
    bool hitThis = false;
    switch (PrimitiveRef::kind(ref)) {
      case PrimitiveKind::Triangle: {
        if (skipTriangles) break;
        const Triangle& tri = triangles_[index];
        if (test == TriangleTest::Watertight) {
          hitThis = intersectWatertight(ray, sheared, tri.v0, tri.v1, tri.v2, tMax, t, u, v);
        } else if (test == TriangleTest::PlaneThenInside) {
          hitThis = intersectPlaneThenInside(ray, tri.v0, tri.edge1(), tri.edge2(), tMax, t, u, v);
        } else {
          hitThis = intersectMollerTrumbore(ray, tri.v0, tri.edge1(), tri.edge2(), tMax, t, u, v);
        }
        break;
      }
#define PRISM_SHAPE_LEAF_TEST(Shape, plural)            \
  case PrimitiveKind::Shape:                            \
    hitThis = plural##_[index].intersect(ray, tMax, t); \
    break;
        PRISM_SHAPE_KINDS(PRISM_SHAPE_LEAF_TEST)
#undef PRISM_SHAPE_LEAF_TEST
      case PrimitiveKind::Plane:
        break;
    }
    if (hitThis) {
      tMax = t;
      hit = {t, ref, u, v};
      found = true;
      if constexpr (kAnyHit) return true;
    }
  }
  return found;
}

template <bool kAnyHit>
bool SceneGeometry::intersectLeafPacked(const Ray& ray, const WatertightRay& sheared,
                                        uint32_t firstPack, uint32_t packCount, float& tMax,
                                        HitRecord& hit) const {
  if (firstPack & kPacklessLeaf) {
    return intersectLeaf<kAnyHit>(ray, sheared, firstPack & ~kPacklessLeaf, packCount, true, tMax,
                                  hit);
  }
  const bool watertight = triangleTest_ == TriangleTest::Watertight;
  bool found = false;
  for (uint32_t p = firstPack; p < firstPack + packCount; ++p) {
    const TrianglePack4& pack = packs_[p].triangles;
    simd::Float4 t, u, v;
    const uint32_t mask = watertight ? intersectWatertight4(ray, sheared, pack, tMax, t, u, v)
                                     : intersectMollerTrumbore4(ray, pack, tMax, t, u, v);
    if constexpr (kAnyHit) {
      if (mask != 0) return true;
    } else {
      const PackHit best = closestLane(mask, t, u, v);
      if (best.lane >= 0) {
        tMax = best.t;
        // Packed triangles are numbered by their lane: pack · 4 + lane.
        const uint32_t index = p * TrianglePack4::kWidth + static_cast<uint32_t>(best.lane);
        hit = {best.t, PrimitiveRef::make(PrimitiveKind::Triangle, index), best.u, best.v};
        found = true;
      }
    }
  }
  const LeafPack& leaf = packs_[firstPack];
  if (leaf.hasOtherKinds) {
    found |= intersectLeaf<kAnyHit>(ray, sheared, leaf.leafFirst, leaf.leafCount, true, tMax, hit);
  }
  return found;
}

}  // namespace prism
