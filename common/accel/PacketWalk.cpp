// Eight rays at a time: the packet walks for coherent rays (a tile's primary rays, their
// shadow rays), |simd::PacketVector| rays to a vector test (compiled once per instruction set;
// accel/IsaVariant.h). Each ray gets the hit the single-ray walk finds for it.
#include <cstring>
#include <limits>

#include "accel/LeafTests.h"
#include "accel/SceneGeometry.h"
#include "accel/WideBvhPacket.h"
#include "geometry/SphereRays.h"
#include "geometry/TriangleMollerTrumboreRays.h"
#include "util/ScratchArray.h"

namespace prism {
namespace {

// A packet's leaf test puts a vector's rays (four or eight) in the lanes, one triangle a test,
// when at least this many of them reach the leaf; fewer take their single-ray test (four
// triangles a test). Measured: with four lanes 2 cost the big meshes more than 3; with eight,
// 3 to 5 are level and 2 a little slower on the grid's shadow rays.
constexpr int kMinRaysPerLaneTest = 3;

}  // namespace

bool SceneGeometry::onlySpheres(uint32_t first, uint32_t count) const {
  for (uint32_t i = first; i < first + count; ++i) {
    if (PrimitiveRef::kind(leafRefs_[i]) != PrimitiveKind::Sphere) return false;
  }
  return true;
}

namespace {

// What a vector of rays has hit so far in one leaf: each lane's limit (its closest hit's t,
// shrinking as the single-ray test's tMax does; -inf where its ray is outside the walk or,
// any-hit, has hit) and that hit.
template <bool kAnyHit, class V>
struct LaneHits {
  using M = simd::MaskOf<V>;
  static constexpr float kInfinity = std::numeric_limits<float>::infinity();

  uint32_t active;  // the lanes whose rays reach the leaf
  V limit;
  V bestU{}, bestV{};
  M bestRef{};  // the hit primitive's PrimitiveRef, as int32 lanes
  uint32_t hitLanes = 0;

  // Records lanes `inside` hitting primitive `ref` at t; false once an any-hit walk is done.
  bool record(uint32_t m, const M& inside, const V& t, const V& u, const V& v, uint32_t ref) {
    hitLanes |= m;
    if constexpr (kAnyHit) {
      if (hitLanes == active) return false;
      limit = simd::select<V>(inside, simd::broadcast<V>(-kInfinity), limit);
    } else {
      limit = simd::select<V>(inside, t, limit);
      bestU = simd::select<V>(inside, u, bestU);
      bestV = simd::select<V>(inside, v, bestV);
      bestRef = simd::selectInt<M>(inside, M{} + static_cast<int32_t>(ref), bestRef);
    }
    return true;
  }
};

// A leaf of spheres alone (refs: its entries) against the lanes, in leaf order.
template <bool kAnyHit, class V>
inline void sphereLanes(const RayLanes<V>& r, const Sphere* spheres, const uint32_t* refs,
                        uint32_t count, LaneHits<kAnyHit, V>& hits) {
  for (uint32_t i = 0; i < count; ++i) {
    V t;
    simd::MaskOf<V> inside;
    const uint32_t m =
        intersectSphereRays(r, spheres[PrimitiveRef::index(refs[i])], hits.limit, t, inside);
    if (m != 0 && !hits.record(m, inside, t, V{}, V{}, refs[i])) return;
  }
}

// A leaf's triangle packs [firstPack, firstPack + packCount) against the lanes, one triangle a
// test, in pack and lane order; an any-hit walk stops once every ray of the lanes has hit.
template <bool kAnyHit, class V>
inline void trianglePackLanes(const RayLanes<V>& r, const SceneGeometry::LeafPack* packs,
                              uint32_t firstPack, uint32_t packCount, LaneHits<kAnyHit, V>& hits) {
  for (uint32_t p = firstPack; p < firstPack + packCount; ++p) {
    const TrianglePack4& pack = packs[p].triangles;
    for (int lane = 0; lane < TrianglePack4::kWidth; ++lane) {
      if (std::isnan(pack.v0[0][lane])) continue;  // an unused lane
      float v0[3], e1[3], e2[3];
      for (int a = 0; a < 3; ++a) {
        v0[a] = pack.v0[a][lane];
        e1[a] = pack.v1[a][lane] - v0[a];
        e2[a] = pack.v2[a][lane] - v0[a];
      }
      V t, u, v;
      simd::MaskOf<V> inside;
      const uint32_t m = intersectMollerTrumboreRays(r, v0, e1, e2, hits.limit, t, u, v, inside);
      if (m == 0) continue;
      // Packed triangles are numbered by their lane: pack · 4 + lane.
      const uint32_t ref = PrimitiveRef::make(
          PrimitiveKind::Triangle, p * TrianglePack4::kWidth + static_cast<uint32_t>(lane));
      if (!hits.record(m, inside, t, u, v, ref)) return;
    }
  }
}

}  // namespace

template <bool kAnyHit, class V>
uint32_t SceneGeometry::intersectLeafRays8(const Ray* rays, const RayPacket8& packet,
                                           uint32_t firstPack, uint32_t packCount, uint32_t mask,
                                           float* tMax, HitRecord* hits) const {
  using M = simd::MaskOf<V>;
  constexpr int kLanes = sizeof(V) / sizeof(float);
  constexpr uint32_t kAllLanes = (1u << kLanes) - 1;
  uint32_t hitRays = 0;
  auto oneByOne = [&](uint32_t some) {
    for (; some != 0; some &= some - 1) {
      const int i = simd::firstLane(some);
      if (intersectLeafPacked<kAnyHit>(rays[i], shearFor(rays[i]), firstPack, packCount, tMax[i],
                                       hits[i])) {
        hitRays |= 1u << i;
      }
    }
  };
  // Cones in the leaf, spheres beside triangles, or the watertight test (its shear is the
  // ray's own): the rays one by one. Leaves of spheres alone and of packed triangles alone
  // put the rays in the lanes.
  const bool sphereLeaf =
      (firstPack & kPacklessLeaf) && onlySpheres(firstPack & ~kPacklessLeaf, packCount);
  if (!sphereLeaf && ((firstPack & kPacklessLeaf) || packs_[firstPack].hasOtherKinds ||
                      triangleTest_ == TriangleTest::Watertight)) {
    oneByOne(mask);
    return hitRays;
  }
  constexpr float kInfinity = std::numeric_limits<float>::infinity();
  // The rays a vector at a time, each primitive in the order a single ray tests them, every
  // lane keeping its own shrinking tMax: the closest hit and its ties come out as they do ray
  // by ray.
  for (int at = 0; at < RayPacket8::kSize; at += kLanes) {
    const uint32_t active = mask >> at & kAllLanes;
    if (active == 0) continue;
    // With few of the lanes' rays reaching the leaf, four triangles per test against one ray
    // wastes fewer lanes than one triangle against all of them.
    if (simd::laneCount(active) < kMinRaysPerLaneTest) {
      oneByOne(active << at);
      continue;
    }
    auto lanes = [&](const float* values) { return simd::load<V>(values + at); };
    const RayLanes<V> r{lanes(packet.rayOrigin[0]),    lanes(packet.rayOrigin[1]),
                        lanes(packet.rayOrigin[2]),    lanes(packet.rayDirection[0]),
                        lanes(packet.rayDirection[1]), lanes(packet.rayDirection[2]),
                        lanes(packet.rayTMin)};
    // Lanes of rays outside the mask look no further than -inf: nothing hits there.
    LaneHits<kAnyHit, V> found{active, simd::select<V>(simd::lanesOf<M>(active), lanes(tMax),
                                                       simd::broadcast<V>(-kInfinity))};
    if (sphereLeaf) {
      const uint32_t first = firstPack & ~kPacklessLeaf;
      sphereLanes(r, spheres_.data(), leafRefs_.data() + first, packCount, found);
    } else {
      trianglePackLanes(r, packs_.data(), firstPack, packCount, found);
    }
    const uint32_t hitLanes = found.hitLanes;
    if constexpr (!kAnyHit) {
      // One store for the lanes: the next box test reads them as a vector.
      simd::store(tMax + at, simd::select<V>(simd::lanesOf<M>(hitLanes), found.limit, lanes(tMax)));
      for (uint32_t m = hitLanes; m != 0; m &= m - 1) {
        const int lane = simd::firstLane(m);
        hits[at + lane] = {found.limit[lane], static_cast<uint32_t>(found.bestRef[lane]),
                           found.bestU[lane], found.bestV[lane]};
      }
    }
    hitRays |= hitLanes << at;
  }
  return hitRays;
}

namespace {

uint32_t liveRays(const Ray* rays, int count) {
  uint32_t mask = 0;
  for (int i = 0; i < count; ++i) mask |= (rays[i].tMax >= rays[i].tMin ? 1u : 0u) << i;
  return mask;
}

}  // namespace

static_assert(SceneGeometry::kPacketSize == RayPacket8::kSize);

template <class V>
void SceneGeometry::intersect8Lanes(const Ray* rays, int count, HitRecord* hits,
                                    bool* found) const {
  const uint32_t live = liveRays(rays, count);
  for (int i = 0; i < count; ++i) found[i] = false;
  if (!packed_) {  // no packed wide walk: one ray at a time
    for (int i = 0; i < count; ++i)
      found[i] = (live >> i & 1u) && Kernels::intersect(*this, rays[i], hits[i]);
    return;
  }
  if (live == 0) return;  // nothing to trace (and no ray to fill the packet's lanes with)
  const RayPacket8 packet(rays, live);
  if (!packet.coherent) {
    for (int i = 0; i < count; ++i)
      found[i] = (live >> i & 1u) && Kernels::intersect(*this, rays[i], hits[i]);
    return;
  }
  alignas(32) float tMax[RayPacket8::kSize];
  std::memcpy(tMax, packet.rayTMax, sizeof(tMax));
  const uint32_t hitMask = traversePacket<false, V>(
      wideBvh_, packet, live, tMax,
      [&](uint32_t firstPack, uint32_t packCount, uint32_t mask, float* rayTMax) {
        return intersectLeafRays8<false, V>(rays, packet, firstPack, packCount, mask, rayTMax,
                                            hits);
      });
  int plane[RayPacket8::kSize];
  const uint32_t planeMask = planes_.empty() ? 0u : planeLanes<V>(packet, live, tMax, plane);
  for (uint32_t m = live; m != 0; m &= m - 1) {
    const int i = simd::firstLane(m);
    found[i] = ((hitMask | planeMask) >> i & 1u) != 0;
    if (planeMask >> i & 1u) {
      hits[i] = {tMax[i], PrimitiveRef::make(PrimitiveKind::Plane, static_cast<uint32_t>(plane[i])),
                 0.0f, 0.0f};
    }
  }
}

template <class V>
uint32_t SceneGeometry::planeLanes(const RayPacket8& packet, uint32_t live, float* tMax,
                                   int* plane) const {
  using M = simd::MaskOf<V>;
  constexpr int kWidth = static_cast<int>(sizeof(V) / sizeof(float));
  uint32_t hit = 0;
  for (int at = 0; at < RayPacket8::kSize; at += kWidth) {
    const auto lanes = [&](const float* p) { return simd::load<V>(p + at); };
    V limit = lanes(tMax);
    M which = M{} - 1;  // the plane each lane hits, -1 for none
    M anyPlane = M{};
    for (uint32_t p = 0; p < planes_.size(); ++p) {
      // Plane::intersect: dot(n, d), then t = (offset - dot(n, o)) / dot(n, d).
      const Vec3& n = planes_[p].normal;
      const V denominator = n.x * lanes(packet.rayDirection[0]) +
                            n.y * lanes(packet.rayDirection[1]) +
                            n.z * lanes(packet.rayDirection[2]);
      const V t = (planes_[p].offset -
                   (n.x * lanes(packet.rayOrigin[0]) + n.y * lanes(packet.rayOrigin[1]) +
                    n.z * lanes(packet.rayOrigin[2]))) /
                  denominator;
      const M meets = (denominator != 0.0f) & (t > lanes(packet.rayTMin)) & (t < limit);
      limit = simd::select<V>(meets, t, limit);
      which = simd::selectInt(meets, M{} + static_cast<int32_t>(p), which);
      anyPlane |= meets;
    }
    simd::store(tMax + at, limit);
    if (plane != nullptr) {
      for (int k = 0; k < kWidth; ++k) plane[at + k] = which[k];
    }
    hit |= simd::laneMask(anyPlane) << at;
  }
  return hit & live;
}

template <class V>
void SceneGeometry::occluded8Lanes(const Ray* rays, int count, bool* blocked) const {
  uint32_t live = liveRays(rays, count);
  for (int i = 0; i < count; ++i) blocked[i] = false;
  if (!packed_) {  // no packed wide walk: one ray at a time
    for (int i = 0; i < count; ++i)
      blocked[i] = (live >> i & 1u) && Kernels::occluded(*this, rays[i]);
    return;
  }
  if (live == 0) return;  // nothing to trace (and no ray to fill the packet's lanes with)
  const RayPacket8 packet(rays, live);
  // Planes first, all rays at once, as occluded() tests them; a blocked ray leaves the packet
  // (whose bounds, taken over every ray, stay conservative for the others).
  if (!planes_.empty()) {
    alignas(32) float tMax[RayPacket8::kSize];
    std::memcpy(tMax, packet.rayTMax, sizeof(tMax));
    const uint32_t byPlane = planeLanes<V>(packet, live, tMax, nullptr);
    for (uint32_t m = byPlane; m != 0; m &= m - 1) blocked[simd::firstLane(m)] = true;
    live &= ~byPlane;
    if (live == 0) return;
  }
  if (!packet.coherent) {
    for (uint32_t m = live; m != 0; m &= m - 1) {
      const int i = simd::firstLane(m);
      blocked[i] = Kernels::occluded(*this, rays[i]);
    }
    return;
  }
  alignas(32) float tMax[RayPacket8::kSize];
  std::memcpy(tMax, packet.rayTMax, sizeof(tMax));
  ScratchArray<HitRecord, RayPacket8::kSize> ignored;  // any-hit walks write but never read them
  const uint32_t hitMask = traversePacket<true, V>(
      wideBvh_, packet, live, tMax,
      [&](uint32_t firstPack, uint32_t packCount, uint32_t mask, float* rayTMax) {
        return intersectLeafRays8<true, V>(rays, packet, firstPack, packCount, mask, rayTMax,
                                           ignored.data());
      });
  for (uint32_t m = hitMask; m != 0; m &= m - 1) blocked[simd::firstLane(m)] = true;
}

bool SceneGeometry::coherentDirections(const Ray* rays, uint32_t live) {
  if (live == 0) return false;
  const Vec3 first = rays[simd::firstLane(live)].direction;
  Vec3 low = first, high = first;
  for (uint32_t m = live & (live - 1); m != 0; m &= m - 1) {
    const Vec3& d = rays[simd::firstLane(m)].direction;
    low = glm::min(low, d);
    high = glm::max(high, d);
  }
  for (int a = 0; a < 3; ++a) {
    if (!(high[a] - low[a] <= RayPacket8::kMaxDirectionSpread)) return false;
    if (low[a] < 0.0f && high[a] > 0.0f) return false;
  }
  return true;
}

void SceneGeometry::Kernels::intersect8(const SceneGeometry& g, const Ray* rays, int count,
                                        HitRecord* hits, bool* found) {
  g.intersect8Lanes<simd::PacketVector>(rays, count, hits, found);
}

void SceneGeometry::Kernels::occluded8(const SceneGeometry& g, const Ray* rays, int count,
                                       bool* blocked) {
  g.occluded8Lanes<simd::PacketVector>(rays, count, blocked);
}

}  // namespace prism
