// The render-ready scene a rank builds from a SceneDescription: primitives in BVH order,
// materials, lights, camera and environment. Immutable once built and shared by all threads.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "accel/Bvh.h"
#include "accel/WideBvh.h"
#include "geometry/Cone.h"
#include "geometry/HitRecord.h"
#include "geometry/Plane.h"
#include "geometry/Sphere.h"
#include "geometry/Triangle.h"
#include "geometry/TrianglePack4.h"
#include "geometry/TriangleWatertight.h"
#include "scene/Camera.h"
#include "scene/CubeMap.h"
#include "scene/SceneDescription.h"

namespace prism {

// A caustic caster as the photon emitter sees it: a bounding sphere, or an infinite plane.
struct RayPacket8;

struct CasterBounds {
  bool plane = false;
  Vec3 center{0.0f};  // sphere
  float radius = 0.0f;
  Vec3 normal{0.0f};  // plane: dot(normal, x) == offset
  float offset = 0.0f;
};

// How rays walk the scene. Both find the same closest hits (tests/common/scene/Scene_test.cpp);
// the binary walk is the reference the fast one is measured and tested against.
enum class Traversal {
  WideSimd,          // 8-wide BVH collapsed from the binary one, triangles tested 4 at a time
  WideScalarLeaves,  // the same wide BVH, triangles one at a time (measures what packs buy)
  BinaryScalar       // the binary SAH BVH, one box and one primitive at a time
};

struct SceneBuildStats {
  size_t spheres = 0, planes = 0, cones = 0, triangles = 0;
  size_t coneSegments = 0;         // the cones' entries in the BVH (a slanted cone enters in parts)
  BvhBuildStats bvh;               // the binary SAH build
  bool binaryBvhReleased = false;  // the wide walk dropped the binary tree once collapsed
  WideBvhStats wideBvh;            // empty under Traversal::BinaryScalar
  size_t packBytes = 0;            // triangle packs of the wide walk
  size_t geometryBytes = 0;        // primitive arrays and mesh shading data, excluding the BVH

  // What the scene holds for finding hits: the trees it keeps and the triangle packs.
  size_t accelerationBytes() const {
    return (binaryBvhReleased ? 0 : bvh.memoryBytes) + wideBvh.memoryBytes + packBytes;
  }
  size_t heldBytes() const { return accelerationBytes() + geometryBytes; }
};

// The caustic bits (kCastsCaustics | kReceivesCaustics) of an object: what its role asks for,
// limited by what its material can do only under Auto (a forced role is taken at its word).
uint8_t causticFlags(CausticRole role, const MaterialDesc& material);

class Scene {
 public:
  explicit Scene(const SceneDescription& description, Traversal traversal = Traversal::WideSimd);
  // The same, with the environment given apart, so a caller that no longer needs the cube-map
  // faces moves them in instead of copying them: for a scene like default.yaml's (six 320x320
  // faces, 7 MiB as floats) the copy and its page faults were a quarter of a small render.
  //   Scene scene(description, std::exchange(description.environment, std::nullopt));
  Scene(const SceneDescription& description, std::optional<CubeMapDesc> environment,
        Traversal traversal = Traversal::WideSimd);

  // Closest hit in (ray.tMin, ray.tMax); the ray direction must be unit length.
  bool intersect(const Ray& ray, HitRecord& hit) const;
  // Whether anything lies on the ray within (ray.tMin, ray.tMax): for shadow rays.
  bool occluded(const Ray& ray) const;
  // Up to eight rays at once, for coherent rays (a pixel tile's primary rays or their shadow
  // rays): the same answers as intersect() and occluded() ray by ray. A ray with tMax < tMin is
  // skipped (found/blocked false).
  static constexpr int kPacketSize = 8;  // rays in one intersect8/occluded8 call, at most
  void intersect8(const Ray* rays, int count, HitRecord* hits, bool* found) const;
  void occluded8(const Ray* rays, int count, bool* blocked) const;
  // Whether the rays in `live` (bit i: rays[i]) pass the packet walk's direction test (one
  // sign per axis, a spread of at most RayPacket8::kMaxDirectionSpread): a cheap check before
  // building a packet. intersect8/occluded8 check again (finite origins and reciprocals too)
  // and send packets that fail down the single-ray walk one by one.
  static bool coherentDirections(const Ray* rays, uint32_t live);
  // How many rays the packet walks test in one vector: 8 (AVX2, chosen at run time where the
  // CPU has it) or 4 (SSE2, any x86-64). The answers are the same; tests and benchmarks set it
  // to compare the two. Throws std::invalid_argument for other counts, or 8 without AVX2.
  int packetLanes() const { return packetLanes_; }
  void setPacketLanes(int lanes);
  // Position, oriented normals and material of a hit found by intersect().
  SurfaceHit surface(const Ray& ray, const HitRecord& hit) const {
    SurfaceHit s;
    surface(ray, hit, s);
    return s;
  }
  // The same written into s, for callers that keep it inside a larger record: a returned
  // SurfaceHit copied there would be read back before its stores retire.
  void surface(const Ray& ray, const HitRecord& hit, SurfaceHit& s) const;

  // Radiance of a ray that hits nothing: the environment's finest level seen along direction,
  // or the background colour.
  Color escapedRadiance(const Vec3& direction) const {
    return environment_ ? environment_->lookup(direction) : background_;
  }
  // The same averaged over the footprint of a ray of unit direction whose direction changes by
  // dDdx, dDdy per pixel (CubeMap's mip levels).
  Color escapedRadiance(const Vec3& direction, const Vec3& dDdx, const Vec3& dDdy) const {
    return environment_ ? environment_->lookup(direction, dDdx, dDdy) : background_;
  }
  // Whether escapedRadiance depends on the footprint: a cube map, not a plain background.
  bool escapedRadianceFiltered() const { return environment_.has_value(); }

  const Camera& camera() const { return camera_; }
  const RenderSettings& settings() const { return settings_; }
  const CausticSettings& causticSettings() const { return caustics_; }
  const std::vector<MaterialDesc>& materials() const { return materials_; }
  // Indexed by a PrimitiveRef of kind Sphere.
  const std::vector<Sphere>& spheres() const { return spheres_; }
  const std::vector<PointLightDesc>& lights() const { return lights_; }
  const Color& ambientLight() const { return ambientLight_; }
  const SceneBuildStats& buildStats() const { return stats_; }
  Traversal traversal() const { return traversal_; }
  // The face index within its mesh of a triangle hit (for comparing hits with other tracers).
  uint32_t meshFace(const HitRecord& hit) const;
  // Objects whose caustic role includes casting, and whose material can send photons on.
  const std::vector<CasterBounds>& causticCasters() const { return casters_; }
  // Bounds of every bounded primitive (planes excluded).
  const Aabb& bounds() const { return bounds_; }

 private:
  struct MeshShading {
    std::vector<Vec3> normals;  // empty: flat shading
    std::vector<uint32_t> indices;
    MaterialId material;
    uint8_t caustic;
    uint32_t firstTriangle;  // number of its first triangle, counting over all meshes in order
  };

  // Triangles of one BVH leaf, four at a time; a leaf's packs are consecutive and the wide BVH
  // points at the first. The leaf's primitive entries are kept for the other kinds it holds.
  struct alignas(16) LeafPack {
    TrianglePack4 triangles;
    uint32_t leafFirst = 0;
    uint16_t leafCount = 0;
    bool hasOtherKinds = false;  // spheres or cones share the leaf
  };
  // A wide-BVH leaf without triangles has no pack: its child field is its first leaf entry with
  // this bit set, its count the entries' count (a pack of four empty lanes per sphere or cone
  // leaf would take 176 bytes and a wasted test).
  static constexpr uint32_t kPacklessLeaf = 1u << 31;

  template <bool kAnyHit>
  bool intersectBounded(const Ray& ray, float& tMax, HitRecord& hit) const;
  template <bool kAnyHit>
  bool intersectLeaf(const Ray& ray, const WatertightRay& sheared, uint32_t first, uint32_t count,
                     bool skipTriangles, float& tMax, HitRecord& hit) const;
  template <bool kAnyHit>
  bool intersectLeafPacked(const Ray& ray, uint32_t firstPack, uint32_t packCount, float& tMax,
                           HitRecord& hit) const;
  template <bool kAnyHit>
  bool intersectLeafPacked(const Ray& ray, const WatertightRay& sheared, uint32_t firstPack,
                           uint32_t packCount, float& tMax, HitRecord& hit) const;
  // The packet walks with V (simd::Float4 or Float8) as the vector of their tests; the *Wide
  // ones are the Float8 walks compiled for AVX2 (Scene.cpp), called where the CPU has it.
  template <class V>
  void intersect8Lanes(const Ray* rays, int count, HitRecord* hits, bool* found) const;
  template <class V>
  void occluded8Lanes(const Ray* rays, int count, bool* blocked) const;
  void intersect8Wide(const Ray* rays, int count, HitRecord* hits, bool* found) const;
  void occluded8Wide(const Ray* rays, int count, bool* blocked) const;
  // A packet's leaf test: the rays in `mask` (bit i: rays[i]) against the leaf, each ray's
  // closest hit (tMax[i], hits[i]) or, any-hit, whether it hits, exactly as
  // intersectLeafPacked finds it alone. Returns the rays that hit.
  template <bool kAnyHit, class V>
  uint32_t intersectLeafRays8(const Ray* rays, const RayPacket8& packet, uint32_t firstPack,
                              uint32_t packCount, uint32_t mask, float* tMax,
                              HitRecord* hits) const;
  // Whether a plane lies on the ray within (tMin, tMax): the shadow test's planes, which are
  // outside the BVH.
  bool blockedByPlane(const Ray& ray) const;
  // The planes against the packet's rays in `live`, |V| rays to a vector, the same arithmetic
  // as Plane::intersect lane by lane: each ray's nearest plane hit before tMax[i] shrinks
  // tMax[i] and sets plane[i] to the plane's index (unless plane is null: shadow rays need not
  // know which). Returns the rays that hit a plane.
  template <class V>
  uint32_t planeLanes(const RayPacket8& packet, uint32_t live, float* tMax, int* plane) const;
  // Whether the leaf entries [first, first + count) are all spheres.
  bool onlySpheres(uint32_t first, uint32_t count) const;
  // The watertight test's per-ray shear, or nothing computed when another test is chosen.
  WatertightRay shearFor(const Ray& ray) const;
  // A triangle by the index its hits carry: into triangles_, or pack · 4 + lane once packed.
  Triangle triangle(uint32_t index) const;
  // Fills packs_ with the description's triangles the leaf entries point at (on `threads`
  // threads) and relabels the wide BVH's leaves to (first pack, pack count).
  void buildTrianglePacks(const SceneDescription& d, unsigned threads);

  RenderSettings settings_;
  CausticSettings caustics_;
  Camera camera_;
  Color background_;
  Color ambientLight_;
  std::optional<CubeMap> environment_;
  std::vector<MaterialDesc> materials_;
  std::vector<PointLightDesc> lights_;
  std::vector<Triangle> triangles_;  // in BVH order; empty once packs hold the triangles
  std::vector<Sphere> spheres_;
  std::vector<Cone> cones_;
  std::vector<Plane> planes_;
  bool testTreeBoxFirst_ = false;  // occluded() asks WideBvh::entersTree before the walk
  std::vector<MeshShading> meshes_;
  std::vector<uint8_t> sphereCaustic_, coneCaustic_, planeCaustic_;  // parallel to the arrays
  std::vector<CasterBounds> casters_;
  Aabb bounds_;
  std::vector<uint32_t> leafRefs_;  // PrimitiveRef per BVH leaf entry (packs: only if mixed)
  Bvh bvh_;                         // empty once the wide BVH is collapsed from it
  Traversal traversal_;
  WideBvh wideBvh_;
  std::vector<LeafPack> packs_;
  bool packed_ = false;  // the wide walk's leaves point at packs (or are packless)
  int packetLanes_ = simd::cpuHasAvx2() ? 8 : 4;
  SceneBuildStats stats_;
};

}  // namespace prism
