#include "scene/Scene.h"

#include <algorithm>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <utility>

#include "accel/WideBvhPacket.h"

#include "geometry/ConeSegments.h"
#include "geometry/SphereRays.h"
#include "geometry/TriangleMollerTrumbore.h"
#include "geometry/TriangleMollerTrumbore4.h"
#include "geometry/TriangleMollerTrumboreRays.h"
#include "geometry/TrianglePlaneInside.h"
#include "geometry/TriangleWatertight4.h"
#include "scene/PrimitiveRef.h"
#include "util/HugePages.h"
#include "util/Parallel.h"
#include "util/ScratchArray.h"

namespace prism {
namespace {

bool anyPositive(const Color& c) {
  return c.x > 0.0f || c.y > 0.0f || c.z > 0.0f;
}

CasterBounds boundingSphere(const Aabb& b) {
  CasterBounds c;
  c.center = b.center();
  c.radius = 0.5f * glm::length(b.extent());
  return c;
}

Triangle meshTriangle(const MeshDesc& mesh, uint32_t meshIndex, uint32_t face) {
  return {mesh.positions[mesh.indices[3 * size_t{face}]],
          mesh.positions[mesh.indices[3 * size_t{face} + 1]],
          mesh.positions[mesh.indices[3 * size_t{face} + 2]], meshIndex, face};
}

// Below this many triangles a scene is gathered and packed on one thread: starting another
// costs more than it saves.
constexpr uint64_t kParallelGatherMinTriangles = 32768;

// A packet's leaf test puts a vector's rays (four or eight) in the lanes, one triangle a test,
// when at least this many of them reach the leaf; fewer take their single-ray test (four
// triangles a test). Measured: with four lanes 2 cost the big meshes more than 3; with eight,
// 3 to 5 are level and 2 a little slower on the grid's shadow rays.
constexpr int kMinRaysPerLaneTest = 3;

// body(begin, end) over [0, count) in chunks of `chunk`, on up to `threads` threads. Every item
// has its own slot, so the result is the same for any number of threads.
void forChunks(uint64_t count, uint64_t chunk, unsigned threads,
               const std::function<void(uint64_t, uint64_t)>& body) {
  parallelFor((count + chunk - 1) / chunk, static_cast<int>(threads),
              [&](uint64_t c) { body(c * chunk, std::min(count, (c + 1) * chunk)); });
}

}  // namespace

uint8_t causticFlags(CausticRole role, const MaterialDesc& m) {
  const bool specular = anyPositive(m.reflectance) || anyPositive(m.transmittance);
  const bool diffuse = m.checker.has_value() || anyPositive(m.diffuse);
  switch (role) {
    case CausticRole::Auto:
      return static_cast<uint8_t>((specular ? kCastsCaustics : 0) |
                                  (diffuse ? kReceivesCaustics : 0));
    case CausticRole::Cast:
      return kCastsCaustics;
    case CausticRole::Receive:
      return kReceivesCaustics;
    case CausticRole::Both:
      return kCastsCaustics | kReceivesCaustics;
    case CausticRole::Off:
      return 0;
  }
  return 0;
}

Scene::Scene(const SceneDescription& d, Traversal traversal) : Scene(d, d.environment, traversal) {}

Scene::Scene(const SceneDescription& d, std::optional<CubeMapDesc> environment, Traversal traversal)
    : settings_(d.render),
      caustics_(d.caustics),
      camera_(d.camera, d.render.width, d.render.height),
      background_(d.background),
      ambientLight_(d.ambientLight),
      materials_(d.materials),
      lights_(d.lights),
      traversal_(traversal) {
  if (environment) environment_.emplace(std::move(*environment));
  if (materials_.empty()) materials_.emplace_back();  // primitives default to material 0

  // The SIMD walk tests four triangles for the price of one: let the SAH fill packs. Spheres and
  // cones, gathered before the triangles, are tested one at a time.
  const bool packed =
      traversal_ == Traversal::WideSimd && settings_.triangleTest != TriangleTest::PlaneThenInside;
  BvhBuildOptions buildOptions;
  buildOptions.primitiveBlock = packed ? TrianglePack4::kWidth : 1;
  const unsigned gatherThreads =
      d.triangleCount() >= kParallelGatherMinTriangles ? buildOptions.threads : 1;

  // Gather every bounded primitive in description order, then reorder by BVH leaf order so a
  // leaf's primitives sit together in memory. Packed triangles are not gathered: the packs read
  // them from the description.
  std::vector<Triangle> triangles;
  std::vector<Sphere> spheres;
  std::vector<Cone> cones;
  std::vector<Aabb> bounds;
  std::vector<uint32_t> refs;
  std::vector<uint8_t> sphereCaustic, coneCaustic;
  const size_t bounded = d.spheres.size() + d.cones.size() + d.triangleCount();
  if (!packed) reserveOnHugePages(triangles, d.triangleCount());
  reserveOnHugePages(bounds, bounded);
  reserveOnHugePages(refs, bounded);
  const auto materialOf = [&](MaterialId id) -> const MaterialDesc& {
    return materials_[id < materials_.size() ? id : 0];
  };
  for (const SphereDesc& s : d.spheres) {
    refs.push_back(PrimitiveRef::make(PrimitiveKind::Sphere, spheres.size()));
    spheres.push_back({s.center, s.radius, s.material});
    bounds.push_back(spheres.back().bounds());
    sphereCaustic.push_back(causticFlags(s.caustic, materialOf(s.material)));
    if (sphereCaustic.back() & kCastsCaustics) {
      CasterBounds c;
      c.center = s.center;
      c.radius = s.radius;
      casters_.push_back(c);
    }
  }
  for (const ConeDesc& c : d.cones) {
    const Cone cone(c.base, c.baseRadius, c.apex, c.apexRadius, c.material);
    const uint8_t caustic = causticFlags(c.caustic, materialOf(c.material));
    if (caustic & kCastsCaustics) casters_.push_back(boundingSphere(cone.bounds()));
    for (const Cone& part : splitForBvh(cone)) {
      refs.push_back(PrimitiveRef::make(PrimitiveKind::Cone, cones.size()));
      cones.push_back(part);
      bounds.push_back(part.bounds());
      coneCaustic.push_back(caustic);
    }
  }
  uint32_t triangleNumber = 0;  // over all meshes, in order
  for (uint32_t m = 0; m < d.meshes.size(); ++m) {
    const MeshDesc& mesh = d.meshes[m];
    const uint8_t caustic = causticFlags(mesh.caustic, materialOf(mesh.material));
    MeshShading shading{{}, {}, mesh.material, caustic, triangleNumber};
    reserveOnHugePages(shading.normals, mesh.normals.size());
    shading.normals.assign(mesh.normals.begin(), mesh.normals.end());
    reserveOnHugePages(shading.indices, mesh.indices.size());
    shading.indices.assign(mesh.indices.begin(), mesh.indices.end());
    meshes_.push_back(std::move(shading));
    if (caustic & kCastsCaustics) {
      Aabb meshBounds;
      for (const Vec3& p : mesh.positions) meshBounds.extend(p);
      if (!meshBounds.empty()) casters_.push_back(boundingSphere(meshBounds));
    }
    const uint32_t faces = static_cast<uint32_t>(mesh.triangleCount());
    const size_t firstEntry = refs.size();
    refs.resize(firstEntry + faces);
    bounds.resize(firstEntry + faces);
    if (!packed) triangles.resize(size_t{triangleNumber} + faces);
    forChunks(faces, 16384, gatherThreads, [&](uint64_t begin, uint64_t end) {
      for (uint32_t f = static_cast<uint32_t>(begin); f < end; ++f) {
        const Triangle tri = meshTriangle(mesh, m, f);
        refs[firstEntry + f] = PrimitiveRef::make(PrimitiveKind::Triangle, triangleNumber + f);
        bounds[firstEntry + f] = tri.bounds();
        if (!packed) triangles[size_t{triangleNumber} + f] = tri;
      }
    });
    triangleNumber += faces;
  }
  for (const PlaneDesc& p : d.planes) {
    const Vec3 n = glm::normalize(p.normal);
    planes_.push_back({n, glm::dot(n, p.point), p.material});
    planeCaustic_.push_back(causticFlags(p.caustic, materialOf(p.material)));
    if (planeCaustic_.back() & kCastsCaustics) {
      CasterBounds c;
      c.plane = true;
      c.normal = planes_.back().normal;
      c.offset = planes_.back().offset;
      casters_.push_back(c);
    }
  }
  for (const Aabb& b : bounds) bounds_.extend(b);

  buildOptions.blockedFrom = static_cast<uint32_t>(spheres.size() + cones.size());
  bvh_.build(bounds, buildOptions);
  std::vector<Aabb>().swap(bounds);
  // Packed triangles go straight from the description into their packs: their leaf entries
  // keep the triangle's number.
  reserveOnHugePages(leafRefs_, refs.size());
  if (!packed) reserveOnHugePages(triangles_, triangles.size());
  for (uint32_t original : bvh_.primitiveOrder()) {
    const uint32_t ref = refs[original];
    const uint32_t index = PrimitiveRef::index(ref);
    switch (PrimitiveRef::kind(ref)) {
      case PrimitiveKind::Triangle:
        if (packed) {
          leafRefs_.push_back(ref);
          break;
        }
        leafRefs_.push_back(PrimitiveRef::make(PrimitiveKind::Triangle, triangles_.size()));
        triangles_.push_back(triangles[index]);
        break;
      case PrimitiveKind::Sphere:
        leafRefs_.push_back(PrimitiveRef::make(PrimitiveKind::Sphere, spheres_.size()));
        spheres_.push_back(spheres[index]);
        sphereCaustic_.push_back(sphereCaustic[index]);
        break;
      case PrimitiveKind::Cone:
        leafRefs_.push_back(PrimitiveRef::make(PrimitiveKind::Cone, cones_.size()));
        cones_.push_back(cones[index]);
        coneCaustic_.push_back(coneCaustic[index]);
        break;
      case PrimitiveKind::Plane:
        break;  // planes are unbounded and never enter the BVH
    }
  }
  // The gathered copies are done with: free them before the wide BVH and its packs are built, so
  // the build's peak stays within scene/MeshBudget.h's estimate.
  std::vector<Triangle>().swap(triangles);
  std::vector<uint32_t>().swap(refs);

  stats_.bvh = bvh_.stats();
  if (traversal_ != Traversal::BinaryScalar) {
    wideBvh_.build(bvh_);
    bvh_ = Bvh();  // the wide walk never reads the binary tree again
    stats_.binaryBvhReleased = true;
  }
  if (packed) {
    buildTrianglePacks(d, gatherThreads);
    packed_ = true;
    // The packs hold every triangle's vertices and source: unless spheres or cones share the
    // leaves, the leaf entries are no longer read.
    if (spheres_.empty() && cones_.empty()) std::vector<uint32_t>().swap(leafRefs_);
  }

  testTreeBoxFirst_ = !planes_.empty() && traversal_ != Traversal::BinaryScalar;

  stats_.spheres = spheres_.size();
  stats_.planes = planes_.size();
  stats_.cones = d.cones.size();
  stats_.coneSegments = cones_.size();
  stats_.triangles = d.triangleCount();
  stats_.wideBvh = wideBvh_.stats();
  stats_.packBytes = packs_.size() * sizeof(LeafPack);
  stats_.geometryBytes = triangles_.capacity() * sizeof(Triangle) +
                         spheres_.size() * sizeof(Sphere) + cones_.size() * sizeof(Cone) +
                         planes_.size() * sizeof(Plane) + leafRefs_.capacity() * sizeof(uint32_t);
  for (const MeshShading& m : meshes_) {
    stats_.geometryBytes += m.normals.size() * sizeof(Vec3) + m.indices.size() * sizeof(uint32_t);
  }
}

void Scene::buildTrianglePacks(const SceneDescription& d, unsigned threads) {
  const auto trianglesIn = [&](uint32_t first, uint32_t count) {
    uint32_t n = 0;
    for (uint32_t k = first; k < first + count; ++k) {
      n += PrimitiveRef::kind(leafRefs_[k]) == PrimitiveKind::Triangle;
    }
    return n;
  };
  if (leafRefs_.size() >= kPacklessLeaf) {
    throw std::length_error("too many primitives for the BVH's leaf numbering");
  }
  // Leaves are relabelled to (first pack, pack count), or to their entries if they hold no
  // triangle, numbering the packs in the wide nodes' order; then every leaf's packs are filled,
  // each in its own slots, on as many threads as were given.
  struct LeafPacks {
    uint32_t first, count, firstPack;
  };
  std::vector<LeafPacks> leaves;
  uint32_t packCount = 0;
  wideBvh_.relabelLeaves([&](uint32_t first, uint32_t count) {
    const uint32_t triangles = trianglesIn(first, count);
    if (triangles == 0) return std::pair<uint32_t, uint32_t>(first | kPacklessLeaf, count);
    leaves.push_back({first, count, packCount});
    const uint32_t packs = (triangles + TrianglePack4::kWidth - 1) / TrianglePack4::kWidth;
    packCount += packs;
    return std::pair<uint32_t, uint32_t>(leaves.back().firstPack, packs);
  });
  reserveOnHugePages(packs_, packCount);
  packs_.resize(packCount);
  // A triangle by its number over all meshes (the meshes' first numbers ascend).
  const auto triangleNumbered = [&](uint32_t number) {
    const auto next = std::upper_bound(
        meshes_.begin(), meshes_.end(), number,
        [](uint32_t n, const MeshShading& mesh) { return n < mesh.firstTriangle; });
    const uint32_t m = static_cast<uint32_t>(next - meshes_.begin()) - 1;
    return meshTriangle(d.meshes[m], m, number - meshes_[m].firstTriangle);
  };
  forChunks(leaves.size(), 4096, threads, [&](uint64_t begin, uint64_t end) {
    for (uint64_t l = begin; l < end; ++l) {
      const LeafPacks& leaf = leaves[l];
      LeafPack& head = packs_[leaf.firstPack];
      head.leafFirst = leaf.first;
      head.leafCount = static_cast<uint16_t>(leaf.count);
      uint32_t pack = leaf.firstPack;
      int lane = 0;
      for (uint32_t i = leaf.first; i < leaf.first + leaf.count; ++i) {
        const uint32_t ref = leafRefs_[i];
        if (PrimitiveRef::kind(ref) != PrimitiveKind::Triangle) {
          head.hasOtherKinds = true;
          continue;
        }
        if (lane == TrianglePack4::kWidth) {
          ++pack;
          lane = 0;
        }
        const uint32_t number = PrimitiveRef::index(ref);
        packs_[pack].triangles.set(lane++, triangleNumbered(number), number);
      }
    }
  });
}

template <bool kAnyHit>
bool Scene::intersectLeaf(const Ray& ray, const WatertightRay& sheared, uint32_t first,
                          uint32_t count, bool skipTriangles, float& tMax, HitRecord& hit) const {
  const TriangleTest test = settings_.triangleTest;
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
      case PrimitiveKind::Sphere:
        hitThis = spheres_[index].intersect(ray, tMax, t);
        break;
      case PrimitiveKind::Cone:
        hitThis = cones_[index].intersect(ray, tMax, t);
        break;
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
bool Scene::intersectLeafPacked(const Ray& ray, uint32_t firstPack, uint32_t packCount, float& tMax,
                                HitRecord& hit) const {
  return intersectLeafPacked<kAnyHit>(ray, shearFor(ray), firstPack, packCount, tMax, hit);
}

template <bool kAnyHit>
bool Scene::intersectLeafPacked(const Ray& ray, const WatertightRay& sheared, uint32_t firstPack,
                                uint32_t packCount, float& tMax, HitRecord& hit) const {
  if (firstPack & kPacklessLeaf) {
    return intersectLeaf<kAnyHit>(ray, sheared, firstPack & ~kPacklessLeaf, packCount, true, tMax,
                                  hit);
  }
  const bool watertight = settings_.triangleTest == TriangleTest::Watertight;
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

template <bool kAnyHit, class V>
uint32_t Scene::intersectLeafRays8(const Ray* rays, const RayPacket8& packet, uint32_t firstPack,
                                   uint32_t packCount, uint32_t mask, float* tMax,
                                   HitRecord* hits) const {
  using M = simd::MaskOf<V>;
  constexpr int kLanes = sizeof(V) / sizeof(float);
  constexpr uint32_t kAllLanes = (1u << kLanes) - 1;
  uint32_t hitRays = 0;
  auto oneByOne = [&](uint32_t some) {
    for (; some != 0; some &= some - 1) {
      const int i = simd::firstLane(some);
      if (intersectLeafPacked<kAnyHit>(rays[i], firstPack, packCount, tMax[i], hits[i])) {
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
                      settings_.triangleTest == TriangleTest::Watertight)) {
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
    V limit =
        simd::select<V>(simd::lanesOf<M>(active), lanes(tMax), simd::broadcast<V>(-kInfinity));
    V bestU{}, bestV{};
    M bestRef{};  // the hit primitive's PrimitiveRef, as int32 lanes
    uint32_t hitLanes = 0;
    // Records lanes `inside` hitting primitive `ref` at t; false once an any-hit walk is done.
    const auto record = [&](uint32_t m, const M& inside, const V& t, const V& u, const V& v,
                            uint32_t ref) {
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
    };
    if (sphereLeaf) {
      const uint32_t first = firstPack & ~kPacklessLeaf;
      for (uint32_t i = first; i < first + packCount; ++i) {
        V t;
        M inside;
        const uint32_t m =
            intersectSphereRays(r, spheres_[PrimitiveRef::index(leafRefs_[i])], limit, t, inside);
        if (m != 0 && !record(m, inside, t, V{}, V{}, leafRefs_[i])) break;
      }
    } else {
      // Any-hit: stop once every ray of these lanes has hit.
      bool looking = true;
      for (uint32_t p = firstPack; p < firstPack + packCount && looking; ++p) {
        const TrianglePack4& pack = packs_[p].triangles;
        for (int lane = 0; lane < TrianglePack4::kWidth; ++lane) {
          if (std::isnan(pack.v0[0][lane])) continue;  // an unused lane
          float v0[3], e1[3], e2[3];
          for (int a = 0; a < 3; ++a) {
            v0[a] = pack.v0[a][lane];
            e1[a] = pack.v1[a][lane] - v0[a];
            e2[a] = pack.v2[a][lane] - v0[a];
          }
          V t, u, v;
          M inside;
          const uint32_t m = intersectMollerTrumboreRays(r, v0, e1, e2, limit, t, u, v, inside);
          if (m == 0) continue;
          // Packed triangles are numbered by their lane: pack · 4 + lane.
          const uint32_t ref = PrimitiveRef::make(
              PrimitiveKind::Triangle, p * TrianglePack4::kWidth + static_cast<uint32_t>(lane));
          if (!record(m, inside, t, u, v, ref)) {
            looking = false;
            break;
          }
        }
      }
    }
    if constexpr (!kAnyHit) {
      // One store for the lanes: the next box test reads them as a vector.
      simd::store(tMax + at, simd::select<V>(simd::lanesOf<M>(hitLanes), limit, lanes(tMax)));
      for (uint32_t m = hitLanes; m != 0; m &= m - 1) {
        const int lane = simd::firstLane(m);
        hits[at + lane] = {limit[lane], static_cast<uint32_t>(bestRef[lane]), bestU[lane],
                           bestV[lane]};
      }
    }
    hitRays |= hitLanes << at;
  }
  return hitRays;
}

bool Scene::blockedByPlane(const Ray& ray) const {
  float t;
  for (const Plane& plane : planes_) {
    if (plane.intersect(ray, ray.tMax, t)) return true;
  }
  return false;
}

bool Scene::onlySpheres(uint32_t first, uint32_t count) const {
  for (uint32_t i = first; i < first + count; ++i) {
    if (PrimitiveRef::kind(leafRefs_[i]) != PrimitiveKind::Sphere) return false;
  }
  return true;
}

WatertightRay Scene::shearFor(const Ray& ray) const {
  return settings_.triangleTest == TriangleTest::Watertight ? WatertightRay(ray.direction)
                                                            : WatertightRay();
}

template <bool kAnyHit>
bool Scene::intersectBounded(const Ray& ray, float& tMax, HitRecord& hit) const {
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

Triangle Scene::triangle(uint32_t index) const {
  if (!packed_) return triangles_[index];
  const TrianglePack4& pack = packs_[index / TrianglePack4::kWidth].triangles;
  const int lane = static_cast<int>(index % TrianglePack4::kWidth);
  Triangle tri;
  for (int a = 0; a < 3; ++a) {
    tri.v0[a] = pack.v0[a][lane];
    tri.v1[a] = pack.v1[a][lane];
    tri.v2[a] = pack.v2[a][lane];
  }
  // The lane keeps the triangle's number over all meshes; the meshes' first numbers ascend.
  const uint32_t number = pack.triangle[lane];
  const auto next =
      std::upper_bound(meshes_.begin(), meshes_.end(), number,
                       [](uint32_t n, const MeshShading& mesh) { return n < mesh.firstTriangle; });
  tri.mesh = static_cast<uint32_t>(next - meshes_.begin()) - 1;
  tri.face = number - meshes_[tri.mesh].firstTriangle;
  return tri;
}

uint32_t Scene::meshFace(const HitRecord& hit) const {
  return triangle(PrimitiveRef::index(hit.primitive)).face;
}

// Not inlined: the packet walks compiled for AVX2 (below) fall back on these for incoherent
// packets, and the single-ray walk compiled for AVX2 measured slower than the build's own.
__attribute__((noinline)) bool Scene::intersect(const Ray& ray, HitRecord& hit) const {
  float tMax = ray.tMax;
  bool found = intersectBounded<false>(ray, tMax, hit);
  for (uint32_t i = 0; i < planes_.size(); ++i) {
    float t;
    if (planes_[i].intersect(ray, tMax, t)) {
      tMax = t;
      hit = {t, PrimitiveRef::make(PrimitiveKind::Plane, i), 0.0f, 0.0f};
      found = true;
    }
  }
  return found;
}

__attribute__((noinline)) bool Scene::occluded(const Ray& ray) const {
  if (blockedByPlane(ray)) return true;
  // A shadow ray from a plane (nearly the only ones that start outside the tree's box, which
  // holds every bounded surface) often misses the whole tree: found without the walk's set-up
  // and root test. Half of the default scene's lone shadow rays; without planes it only costs.
  if (testTreeBoxFirst_ && !wideBvh_.entersTree(ray, ray.tMax)) return false;
  float tMax = ray.tMax;
  HitRecord ignored;
  return intersectBounded<true>(ray, tMax, ignored);
}

namespace {

uint32_t liveRays(const Ray* rays, int count) {
  uint32_t mask = 0;
  for (int i = 0; i < count; ++i) mask |= (rays[i].tMax >= rays[i].tMin ? 1u : 0u) << i;
  return mask;
}

}  // namespace

static_assert(Scene::kPacketSize == RayPacket8::kSize);

template <class V>
void Scene::intersect8Lanes(const Ray* rays, int count, HitRecord* hits, bool* found) const {
  const uint32_t live = liveRays(rays, count);
  for (int i = 0; i < count; ++i) found[i] = false;
  if (!packed_) {  // no packed wide walk: one ray at a time
    for (int i = 0; i < count; ++i) found[i] = (live >> i & 1u) && intersect(rays[i], hits[i]);
    return;
  }
  if (live == 0) return;  // nothing to trace (and no ray to fill the packet's lanes with)
  const RayPacket8 packet(rays, live);
  if (!packet.coherent) {
    for (int i = 0; i < count; ++i) found[i] = (live >> i & 1u) && intersect(rays[i], hits[i]);
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
uint32_t Scene::planeLanes(const RayPacket8& packet, uint32_t live, float* tMax, int* plane) const {
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
void Scene::occluded8Lanes(const Ray* rays, int count, bool* blocked) const {
  uint32_t live = liveRays(rays, count);
  for (int i = 0; i < count; ++i) blocked[i] = false;
  if (!packed_) {  // no packed wide walk: one ray at a time
    for (int i = 0; i < count; ++i) blocked[i] = (live >> i & 1u) && occluded(rays[i]);
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
      blocked[i] = occluded(rays[i]);
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

// The packet walks, eight rays to a vector, compiled for AVX2 whatever the build targets and
// chosen at run time on CPUs that have it (Scene::packetLanes). `flatten` inlines the whole walk
// into these two functions, so all of it is compiled for AVX2: templates instantiated here would
// otherwise be compiled for the build's own target. No fused multiply-add either way
// (-ffp-contract=off), so the answers are the same bit for bit.
#if defined(__x86_64__) && !defined(__AVX2__)
#define PRISM_AVX2_KERNEL __attribute__((target("avx2"), flatten))
#else
#define PRISM_AVX2_KERNEL
#endif

PRISM_AVX2_KERNEL void Scene::intersect8Wide(const Ray* rays, int count, HitRecord* hits,
                                             bool* found) const {
  intersect8Lanes<simd::Float8>(rays, count, hits, found);
}

PRISM_AVX2_KERNEL void Scene::occluded8Wide(const Ray* rays, int count, bool* blocked) const {
  occluded8Lanes<simd::Float8>(rays, count, blocked);
}

bool Scene::coherentDirections(const Ray* rays, uint32_t live) {
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

void Scene::intersect8(const Ray* rays, int count, HitRecord* hits, bool* found) const {
  if (packetLanes_ == 8) {
    intersect8Wide(rays, count, hits, found);
  } else {
    intersect8Lanes<simd::Float4>(rays, count, hits, found);
  }
}

void Scene::occluded8(const Ray* rays, int count, bool* blocked) const {
  if (packetLanes_ == 8) {
    occluded8Wide(rays, count, blocked);
  } else {
    occluded8Lanes<simd::Float4>(rays, count, blocked);
  }
}

void Scene::setPacketLanes(int lanes) {
  if (lanes != 4 && lanes != 8) throw std::invalid_argument("packet lanes must be 4 or 8");
  if (lanes == 8 && !simd::cpuHasAvx2()) {
    throw std::invalid_argument("8 packet lanes need a CPU with AVX2");
  }
  packetLanes_ = lanes;
}

namespace {

// What Scene::surface does for every kind once the kind has found the point, its rounding bound
// and its normals. Inlined into each kind's branch: with one tail after the switch, GCC kept
// the branches' results in a shared stack slot and copied them on in eight-byte loads from
// four-byte stores (a store-forwarding stall, a third of what a plane's or a sphere's surface
// cost).
[[gnu::always_inline]] inline void finishSurface(const Ray& ray, float t, const Vec3& position,
                                                 Vec3 positionError, Vec3 geometric, Vec3 shading,
                                                 SurfaceHit& s) {
  // Coordinate by coordinate: copied whole, the point went through the stack the same way.
  s.position.x = position.x;
  s.position.y = position.y;
  s.position.z = position.z;
  // Orient both normals towards the incoming ray; remember which side was hit for refraction.
  s.frontFace = glm::dot(ray.direction, geometric) < 0.0f;
  if (!s.frontFace) {
    geometric = -geometric;
    shading = -shading;
  }
  // Interpolated normals can lean past the geometric horizon at silhouettes; keep them on the
  // ray's side so shading and secondary rays stay consistent.
  if (glm::dot(shading, geometric) < 0.0f) shading = geometric;
  s.geometricNormal = geometric;
  s.shadingNormal = shading;
  positionError += hitDistanceError(t, ray.direction);
  s.leavingDistance = leavingDistance(position, positionError, geometric);
}

}  // namespace

void Scene::surface(const Ray& ray, const HitRecord& hit, SurfaceHit& s) const {
  // Each kind puts the point back on its surface with a bound on the rounding per axis
  // (math/RayOffset.h): rays leaving it start just outside that bound, widened by the rounding of
  // the incoming ray's distance (surfaces nearer each other than that cannot be ordered).
  const uint32_t index = PrimitiveRef::index(hit.primitive);
  switch (PrimitiveRef::kind(hit.primitive)) {
    case PrimitiveKind::Triangle: {
      const Triangle tri = triangle(index);
      const MeshShading& mesh = meshes_[tri.mesh];
      Vec3 positionError;
      const Vec3 position = tri.pointAt(hit.u, hit.v, positionError);
      Vec3 geometric = glm::normalize(glm::cross(tri.edge1(), tri.edge2()));
      Vec3 shading = geometric;
      if (!mesh.normals.empty()) {
        const uint32_t* corner = &mesh.indices[3 * tri.face];
        const Vec3 interpolated = (1.0f - hit.u - hit.v) * mesh.normals[corner[0]] +
                                  hit.u * mesh.normals[corner[1]] + hit.v * mesh.normals[corner[2]];
        const float length = glm::length(interpolated);
        if (length > 0.0f) shading = interpolated / length;
        // Authored normals define outside; the winding order may disagree with them.
        if (glm::dot(geometric, shading) < 0.0f) geometric = -geometric;
      }
      s.material = mesh.material;
      s.caustic = mesh.caustic;
      finishSurface(ray, hit.t, position, positionError, geometric, shading, s);
      return;
    }
    case PrimitiveKind::Sphere: {
      const Vec3 normal = spheres_[index].normalAt(ray.at(hit.t));
      Vec3 positionError;
      const Vec3 position = spheres_[index].pointAlong(normal, positionError);
      s.material = spheres_[index].material;
      s.caustic = sphereCaustic_[index];
      finishSurface(ray, hit.t, position, positionError, normal, normal, s);
      return;
    }
    case PrimitiveKind::Cone: {
      Vec3 positionError, normal;
      const Vec3 position = cones_[index].surfacePoint(ray.at(hit.t), positionError, normal);
      s.material = cones_[index].material();
      s.caustic = coneCaustic_[index];
      finishSurface(ray, hit.t, position, positionError, normal, normal, s);
      return;
    }
    case PrimitiveKind::Plane: {
      Vec3 positionError;
      const Vec3 position = planes_[index].surfacePoint(ray.at(hit.t), positionError);
      s.material = planes_[index].material;
      s.caustic = planeCaustic_[index];
      finishSurface(ray, hit.t, position, positionError, planes_[index].normal,
                    planes_[index].normal, s);
      return;
    }
  }
}

}  // namespace prism
