#include "scene/Scene.h"

#include <utility>

#include "accel/WideBvhPacket.h"

#include "geometry/TriangleMollerTrumbore.h"
#include "geometry/TrianglePlaneInside.h"
#include "scene/PrimitiveRef.h"

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

  // Gather every bounded primitive in description order, then reorder by BVH leaf order so a
  // leaf's primitives sit together in memory.
  std::vector<Triangle> triangles;
  std::vector<Sphere> spheres;
  std::vector<Cone> cones;
  std::vector<Aabb> bounds;
  std::vector<uint32_t> refs;
  std::vector<uint8_t> sphereCaustic, coneCaustic;
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
    refs.push_back(PrimitiveRef::make(PrimitiveKind::Cone, cones.size()));
    cones.emplace_back(c.base, c.baseRadius, c.apex, c.apexRadius, c.material);
    bounds.push_back(cones.back().bounds());
    coneCaustic.push_back(causticFlags(c.caustic, materialOf(c.material)));
    if (coneCaustic.back() & kCastsCaustics) casters_.push_back(boundingSphere(bounds.back()));
  }
  for (uint32_t m = 0; m < d.meshes.size(); ++m) {
    const MeshDesc& mesh = d.meshes[m];
    const uint8_t caustic = causticFlags(mesh.caustic, materialOf(mesh.material));
    meshes_.push_back({mesh.normals, mesh.indices, mesh.material, caustic});
    if (caustic & kCastsCaustics) {
      Aabb meshBounds;
      for (const Vec3& p : mesh.positions) meshBounds.extend(p);
      if (!meshBounds.empty()) casters_.push_back(boundingSphere(meshBounds));
    }
    for (uint32_t f = 0; f < mesh.triangleCount(); ++f) {
      const Vec3& a = mesh.positions[mesh.indices[3 * f]];
      const Vec3& b = mesh.positions[mesh.indices[3 * f + 1]];
      const Vec3& c = mesh.positions[mesh.indices[3 * f + 2]];
      refs.push_back(PrimitiveRef::make(PrimitiveKind::Triangle, triangles.size()));
      triangles.push_back({a, b - a, c - a, m, f});
      bounds.push_back(triangles.back().bounds());
    }
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

  // The SIMD walk tests four triangles for the price of one: let the SAH fill packs.
  const bool packed =
      traversal_ == Traversal::WideSimd && settings_.triangleTest == TriangleTest::MollerTrumbore;
  BvhBuildOptions buildOptions;
  buildOptions.primitiveBlock = packed ? TrianglePack4::kWidth : 1;
  bvh_.build(bounds, buildOptions);
  leafRefs_.reserve(refs.size());
  for (uint32_t original : bvh_.primitiveOrder()) {
    const uint32_t ref = refs[original];
    const uint32_t index = PrimitiveRef::index(ref);
    switch (PrimitiveRef::kind(ref)) {
      case PrimitiveKind::Triangle:
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
  // The gathered copies are done with: free them before the wide BVH and its packs are built,
  // so the build's peak stays within scene/MeshBudget.h's estimate.
  std::vector<Triangle>().swap(triangles);
  std::vector<Aabb>().swap(bounds);
  std::vector<uint32_t>().swap(refs);

  if (traversal_ != Traversal::BinaryScalar) wideBvh_.build(bvh_);
  if (packed) buildTrianglePacks();

  stats_.spheres = spheres_.size();
  stats_.planes = planes_.size();
  stats_.cones = cones_.size();
  stats_.triangles = triangles_.size();
  stats_.bvh = bvh_.stats();
  stats_.wideBvh = wideBvh_.stats();
  stats_.packBytes = packs_.size() * sizeof(LeafPack);
  stats_.geometryBytes = triangles_.size() * sizeof(Triangle) + spheres_.size() * sizeof(Sphere) +
                         cones_.size() * sizeof(Cone) + planes_.size() * sizeof(Plane) +
                         leafRefs_.size() * sizeof(uint32_t);
  for (const MeshShading& m : meshes_) {
    stats_.geometryBytes += m.normals.size() * sizeof(Vec3) + m.indices.size() * sizeof(uint32_t);
  }
}

void Scene::buildTrianglePacks() {
  // Leaves are relabelled to (first pack, pack count); every leaf gets at least one pack, if
  // only to carry its entries for the spheres and cones.
  wideBvh_.relabelLeaves([&](uint32_t first, uint32_t count) {
    const uint32_t firstPack = static_cast<uint32_t>(packs_.size());
    packs_.emplace_back();
    packs_.back().leafFirst = first;
    packs_.back().leafCount = static_cast<uint16_t>(count);
    int lane = 0;
    for (uint32_t i = first; i < first + count; ++i) {
      const uint32_t ref = leafRefs_[i];
      if (PrimitiveRef::kind(ref) != PrimitiveKind::Triangle) {
        packs_[firstPack].hasOtherKinds = true;
        continue;
      }
      if (lane == TrianglePack4::kWidth) {
        packs_.emplace_back();
        lane = 0;
      }
      const uint32_t index = PrimitiveRef::index(ref);
      packs_.back().triangles.set(lane++, triangles_[index], index);
    }
    return std::pair<uint32_t, uint32_t>(firstPack,
                                         static_cast<uint32_t>(packs_.size()) - firstPack);
  });
}

template <bool kAnyHit>
bool Scene::intersectLeaf(const Ray& ray, uint32_t first, uint32_t count, bool skipTriangles,
                          float& tMax, HitRecord& hit) const {
  const bool classicTriangleTest = settings_.triangleTest == TriangleTest::PlaneThenInside;
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
        hitThis = classicTriangleTest
                      ? intersectPlaneThenInside(ray, tri.v0, tri.e1, tri.e2, tMax, t, u, v)
                      : intersectMollerTrumbore(ray, tri.v0, tri.e1, tri.e2, tMax, t, u, v);
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
  bool found = false;
  for (uint32_t p = firstPack; p < firstPack + packCount; ++p) {
    const TrianglePack4& pack = packs_[p].triangles;
    if constexpr (kAnyHit) {
      simd::Float4 t, u, v;
      if (intersectMollerTrumbore4(ray, pack, tMax, t, u, v) != 0) return true;
    } else {
      const PackHit best = closestInPack(ray, pack, tMax);
      if (best.lane >= 0) {
        tMax = best.t;
        hit = {best.t, PrimitiveRef::make(PrimitiveKind::Triangle, pack.triangle[best.lane]),
               best.u, best.v};
        found = true;
      }
    }
  }
  const LeafPack& leaf = packs_[firstPack];
  if (leaf.hasOtherKinds) {
    found |= intersectLeaf<kAnyHit>(ray, leaf.leafFirst, leaf.leafCount, true, tMax, hit);
  }
  return found;
}

template <bool kAnyHit>
bool Scene::intersectBounded(const Ray& ray, float& tMax, HitRecord& hit) const {
  if (traversal_ == Traversal::BinaryScalar) {
    return bvh_.traverse(ray, tMax, kAnyHit, [&](uint32_t first, uint32_t count, float& leafTMax) {
      return intersectLeaf<kAnyHit>(ray, first, count, false, leafTMax, hit);
    });
  }
  if (packs_.empty()) {
    return wideBvh_.traverse<kAnyHit>(ray, tMax, [&](uint32_t first, uint32_t count, float& t) {
      return intersectLeaf<kAnyHit>(ray, first, count, false, t, hit);
    });
  }
  return wideBvh_.traverse<kAnyHit>(ray, tMax, [&](uint32_t first, uint32_t count, float& t) {
    return intersectLeafPacked<kAnyHit>(ray, first, count, t, hit);
  });
}

uint32_t Scene::meshFace(const HitRecord& hit) const {
  return triangles_[PrimitiveRef::index(hit.primitive)].face;
}

bool Scene::intersect(const Ray& ray, HitRecord& hit) const {
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

bool Scene::occluded(const Ray& ray) const {
  float tMax = ray.tMax;
  float t;
  for (const Plane& plane : planes_) {
    if (plane.intersect(ray, tMax, t)) return true;
  }
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

void Scene::intersect8(const Ray* rays, int count, HitRecord* hits, bool* found) const {
  const uint32_t live = liveRays(rays, count);
  for (int i = 0; i < count; ++i) found[i] = false;
  if (packs_.empty()) {  // no packed wide walk: one ray at a time
    for (int i = 0; i < count; ++i) found[i] = (live >> i & 1u) && intersect(rays[i], hits[i]);
    return;
  }
  const RayPacket8 packet(rays, live);
  if (!packet.coherent) {
    for (int i = 0; i < count; ++i) found[i] = (live >> i & 1u) && intersect(rays[i], hits[i]);
    return;
  }
  float tMax[RayPacket8::kSize];
  for (int i = 0; i < RayPacket8::kSize; ++i) tMax[i] = i < count ? rays[i].tMax : 0.0f;
  const uint32_t hitMask = traversePacket<false>(
      wideBvh_, packet, live, tMax,
      [&](uint32_t firstPack, uint32_t packCount, uint32_t mask, float* rayTMax) {
        uint32_t hitRays = 0;
        for (; mask != 0; mask &= mask - 1) {
          const int i = simd::firstLane(mask);
          if (intersectLeafPacked<false>(rays[i], firstPack, packCount, rayTMax[i], hits[i])) {
            hitRays |= 1u << i;
          }
        }
        return hitRays;
      });
  for (int i = 0; i < count; ++i) {
    if (!(live >> i & 1u)) continue;
    found[i] = (hitMask >> i & 1u) != 0;
    for (uint32_t p = 0; p < planes_.size(); ++p) {
      float t;
      if (planes_[p].intersect(rays[i], tMax[i], t)) {
        tMax[i] = t;
        hits[i] = {t, PrimitiveRef::make(PrimitiveKind::Plane, p), 0.0f, 0.0f};
        found[i] = true;
      }
    }
  }
}

void Scene::occluded8(const Ray* rays, int count, bool* blocked) const {
  const uint32_t live = liveRays(rays, count);
  for (int i = 0; i < count; ++i) blocked[i] = false;
  if (packs_.empty() || !planes_.empty()) {  // planes first, as occluded() does: one at a time
    for (int i = 0; i < count; ++i) blocked[i] = (live >> i & 1u) && occluded(rays[i]);
    return;
  }
  const RayPacket8 packet(rays, live);
  if (!packet.coherent) {
    for (int i = 0; i < count; ++i) blocked[i] = (live >> i & 1u) && occluded(rays[i]);
    return;
  }
  float tMax[RayPacket8::kSize];
  for (int i = 0; i < RayPacket8::kSize; ++i) tMax[i] = i < count ? rays[i].tMax : 0.0f;
  HitRecord ignored;
  const uint32_t hitMask = traversePacket<true>(
      wideBvh_, packet, live, tMax,
      [&](uint32_t firstPack, uint32_t packCount, uint32_t mask, float* rayTMax) {
        uint32_t hitRays = 0;
        for (; mask != 0; mask &= mask - 1) {
          const int i = simd::firstLane(mask);
          if (intersectLeafPacked<true>(rays[i], firstPack, packCount, rayTMax[i], ignored)) {
            hitRays |= 1u << i;
          }
        }
        return hitRays;
      });
  for (int i = 0; i < count; ++i) blocked[i] = (hitMask >> i & 1u) != 0;
}

SurfaceHit Scene::surface(const Ray& ray, const HitRecord& hit) const {
  SurfaceHit s;
  s.position = ray.at(hit.t);
  const uint32_t index = PrimitiveRef::index(hit.primitive);
  Vec3 geometric, shading;
  switch (PrimitiveRef::kind(hit.primitive)) {
    case PrimitiveKind::Triangle: {
      const Triangle& tri = triangles_[index];
      const MeshShading& mesh = meshes_[tri.mesh];
      geometric = glm::normalize(glm::cross(tri.e1, tri.e2));
      shading = geometric;
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
      break;
    }
    case PrimitiveKind::Sphere:
      geometric = shading = spheres_[index].normalAt(s.position);
      s.material = spheres_[index].material;
      s.caustic = sphereCaustic_[index];
      break;
    case PrimitiveKind::Cone:
      geometric = shading = cones_[index].normalAt(s.position);
      s.material = cones_[index].material();
      s.caustic = coneCaustic_[index];
      break;
    case PrimitiveKind::Plane:
      geometric = shading = planes_[index].normal;
      s.material = planes_[index].material;
      s.caustic = planeCaustic_[index];
      break;
  }
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
  return s;
}

}  // namespace prism
