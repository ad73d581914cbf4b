// The scene's surfaces as rays find them: primitives in BVH leaf order, the BVH (binary, or 8-wide
// collapsed from it), the triangles packed four to a leaf test, and the walks that find hits.
// Built once per rank from the primitives the Scene hands over; immutable after, shared by all
// threads. The walks and leaf tests (SingleRayWalk.cpp, PacketWalk.cpp, SurfaceAt.cpp) are
// compiled once per instruction set; this class calls the set it was given
// (accel/GeometryKernels.h), so a job's ranks all run the same arithmetic.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "accel/Bvh.h"
#include "accel/GeometryKernels.h"
#include "accel/Traversal.h"
#include "accel/WideBvh.h"
#include "geometry/HitRecord.h"
#include "geometry/Plane.h"
#include "geometry/ShapeKinds.h"
#include "geometry/Triangle.h"
#include "geometry/TrianglePack4.h"
#include "geometry/TriangleTest.h"
#include "geometry/TriangleWatertight.h"
#include "util/FieldList.h"
#include "util/InstructionSet.h"

namespace prism {
namespace wire {
template <class T>
struct Fields;
}

struct RayPacket8;

// A mesh as the build reads it: views into arrays (the scene description's) that must outlive
// the build. Normals and indices are copied for shading; positions go into the triangle packs.
struct MeshInput {
  std::span<const Vec3> positions;
  std::span<const uint32_t> indices;          // three per triangle
  std::span<const Vec3> normals;              // one per position, or empty: flat shading
  std::span<const Vec2> uvs;                  // one per position, or empty
  std::span<const Color> colors;              // one per position, or empty
  std::span<const MaterialId> faceMaterials;  // one per triangle, or empty: material for all
  MaterialId material = 0;
  uint8_t caustic = 0;  // kCastsCaustics | kReceivesCaustics

  // Face `face` of this mesh, the mesh numbered meshIndex among the scene's.
  Triangle triangle(uint32_t meshIndex, uint32_t face) const {
    const size_t corner = 3 * size_t{face};
    return {positions[indices[corner]], positions[indices[corner + 1]],
            positions[indices[corner + 2]], meshIndex, face};
  }
};

// Everything the build takes: primitives with their caustic bits, and how to walk them.
struct GeometryInput {
  // Each kind of geometry/ShapeKinds.h whole (the build enters a slanted cone in parts) with
  // its caustic bits: spheres, spheresCaustic, cones, conesCaustic, ...
#define PRISM_SHAPE_INPUT(Shape, plural) \
  std::vector<Shape> plural;             \
  std::vector<uint8_t> plural##Caustic;
  PRISM_SHAPE_KINDS(PRISM_SHAPE_INPUT)
#undef PRISM_SHAPE_INPUT
  std::vector<Plane> planes;  // unbounded: outside the BVH, tested on every ray
  std::vector<uint8_t> planeCaustic;
  std::vector<MeshInput> meshes;
  TriangleTest triangleTest = TriangleTest::MollerTrumbore;
  Traversal traversal = Traversal::WideSimd;
  InstructionSet instructionSet = InstructionSet::Auto;  // resolved by the build

  size_t triangleCount() const {
    size_t n = 0;
    for (const MeshInput& m : meshes) n += m.indices.size() / 3;
    return n;
  }
};

// How many of one kind the scene holds, and their entries in the BVH (a slanted cone enters in
// parts).
struct ShapeCount {
  size_t count = 0;
  size_t bvhParts = 0;
  PRISM_WIRE_FIELDS(count, bvhParts)
};

struct SceneBuildStats {
#define PRISM_SHAPE_COUNT(Shape, plural) ShapeCount plural;
  PRISM_SHAPE_KINDS(PRISM_SHAPE_COUNT)  // spheres, cones, ... (geometry/ShapeKinds.h)
#undef PRISM_SHAPE_COUNT
  size_t planes = 0, triangles = 0;
  BvhBuildStats bvh;               // the binary SAH build
  bool binaryBvhReleased = false;  // the wide walk dropped the binary tree once collapsed
  WideBvhStats wideBvh;            // empty under Traversal::BinaryScalar
  size_t packBytes = 0;            // triangle packs of the wide walk
  size_t geometryBytes = 0;        // primitive arrays and mesh shading data, excluding the BVH

  // What the scene holds for finding hits: the trees it keeps and the triangle packs.
  size_t accelerationBytes() const {
    return (binaryBvhReleased ? 0 : bvh.memoryBytes) + wideBvh.memoryBytes + packBytes;
  }
  size_t heldBytes() const {
    return accelerationBytes() + geometryBytes;
  }
};

class SceneGeometry {
 public:
  // Builds on as many threads as the machine has (big meshes only). The instruction set must
  // be one this process runs (std::invalid_argument otherwise); Auto takes the best.
  explicit SceneGeometry(GeometryInput input);
  // Empty: nothing is hit. What a reader of the wire form (wire/GeometryCodec.h) fills with a
  // geometry built on another rank, member for member, so the walks find the same hits.
  SceneGeometry() : SceneGeometry(GeometryInput{}) {}
  SceneGeometry(const SceneGeometry&) = delete;
  SceneGeometry& operator=(const SceneGeometry&) = delete;
  SceneGeometry(SceneGeometry&&) = default;
  SceneGeometry& operator=(SceneGeometry&&) = default;

  // Closest hit in (ray.tMin, ray.tMax); the ray direction must be unit length.
  bool intersect(const Ray& ray, HitRecord& hit) const {
    return kernels_->intersect(*this, ray, hit);
  }
  // Whether anything lies on the ray within (ray.tMin, ray.tMax): for shadow rays.
  bool occluded(const Ray& ray) const { return kernels_->occluded(*this, ray); }
  // Up to kPacketSize rays at once, the same answers as intersect() and occluded() ray by ray;
  // a ray with tMax < tMin is skipped (found/blocked false).
  static constexpr int kPacketSize = 8;
  // Whether the rays in `live` (bit i: rays[i]) pass the packet walk's direction test (one
  // sign per axis, a spread of at most RayPacket8::kMaxDirectionSpread).
  static bool coherentDirections(const Ray* rays, uint32_t live);
  void intersect8(const Ray* rays, int count, HitRecord* hits, bool* found) const {
    kernels_->intersect8(*this, rays, count, hits, found);
  }
  void occluded8(const Ray* rays, int count, bool* blocked) const {
    kernels_->occluded8(*this, rays, count, blocked);
  }
  // Position, oriented normals, material and caustic bits of a hit found by intersect().
  void surface(const Ray& ray, const HitRecord& hit, SurfaceHit& s) const {
    kernels_->surface(*this, ray, hit, s);
  }

  // The instruction set whose kernels run, and how many rays their packet tests take at once
  // (8 with AVX2, else 4). Another set may be chosen later (tests and benchmarks compare them);
  // it must be one this process runs (std::invalid_argument otherwise).
  InstructionSet instructionSet() const { return kernels_->instructionSet; }
  int packetLanes() const { return kernels_->packetLanes; }
  void useInstructionSet(InstructionSet isa);

  // The face index within its mesh of a triangle hit (for comparing hits with other tracers).
  uint32_t meshFace(const HitRecord& hit) const;
  const std::vector<Sphere>& spheres() const { return spheres_; }  // by a Sphere PrimitiveRef
  const Aabb& bounds() const { return bounds_; }  // of every bounded primitive (no planes)
  const SceneBuildStats& stats() const { return stats_; }
  Traversal traversal() const { return traversal_; }

  // The kernels themselves, one copy per instruction set (accel/GeometryKernels.h holds their
  // addresses). Call them through the members above.
  struct Kernels {
    static bool intersect(const SceneGeometry& g, const Ray& ray, HitRecord& hit);
    static bool occluded(const SceneGeometry& g, const Ray& ray);
    static void intersect8(const SceneGeometry& g, const Ray* rays, int count, HitRecord* hits,
                           bool* found);
    static void occluded8(const SceneGeometry& g, const Ray* rays, int count, bool* blocked);
    static void surface(const SceneGeometry& g, const Ray& ray, const HitRecord& hit,
                        SurfaceHit& s);
  };

  // The parts below are public so that the wire form can name them; their values stay private.
  struct MeshShading {
    std::vector<Vec3> normals;  // empty: flat shading
    std::vector<uint32_t> indices;
    MaterialId material;
    uint8_t caustic;
    uint32_t firstTriangle;     // number of its first triangle, counting over all meshes in order
    std::vector<Vec2> uvs;      // empty: no texture coordinates
    std::vector<Color> colors;  // empty: no vertex colours
    std::vector<MaterialId> faceMaterials;  // empty: material for every face
  };

  // Triangles of one BVH leaf, four at a time; a leaf's packs are consecutive and the wide BVH
  // points at the first. The leaf's primitive entries are kept for the other kinds it holds.
  struct alignas(16) LeafPack {
    TrianglePack4 triangles;
    uint32_t leafFirst = 0;
    uint16_t leafCount = 0;
    bool hasOtherKinds = false;  // shapes (spheres, cones, ...) share the leaf
    uint8_t unused[9] = {};      // what alignment would pad, zeroed: the memory is the wire form
  };
  static_assert(sizeof(LeafPack) == 176);
  // A wide-BVH leaf without triangles has no pack: its child field is its first leaf entry with
  // this bit set, its count the entries' count (a pack of four empty lanes per sphere or cone
  // leaf would take 176 bytes and a wasted test).
  static constexpr uint32_t kPacklessLeaf = 1u << 31;

 private:
  template <class T>
  friend struct wire::Fields;  // the wire form lists the members (wire/GeometryCodec.h)

  // The walks' parts (accel/LeafTests.h, PacketWalk.cpp, SingleRayWalk.cpp).
  template <bool kAnyHit>
  bool intersectBounded(const Ray& ray, float& tMax, HitRecord& hit) const;
  template <bool kAnyHit>
  bool intersectLeaf(const Ray& ray, const WatertightRay& sheared, uint32_t first, uint32_t count,
                     bool skipTriangles, float& tMax, HitRecord& hit) const;
  template <bool kAnyHit>
  bool intersectLeafPacked(const Ray& ray, const WatertightRay& sheared, uint32_t firstPack,
                           uint32_t packCount, float& tMax, HitRecord& hit) const;
  // The packet walks with V (simd::Float4 or Float8) as the vector of their tests.
  template <class V>
  void intersect8Lanes(const Ray* rays, int count, HitRecord* hits, bool* found) const;
  template <class V>
  void occluded8Lanes(const Ray* rays, int count, bool* blocked) const;
  // A packet's leaf test: the rays in `mask` (bit i: rays[i]) against the leaf, each ray's
  // closest hit (tMax[i], hits[i]) or, any-hit, whether it hits, exactly as
  // intersectLeafPacked finds it alone. Returns the rays that hit.
  template <bool kAnyHit, class V>
  uint32_t intersectLeafRays8(const Ray* rays, const RayPacket8& packet, uint32_t firstPack,
                              uint32_t packCount, uint32_t mask, float* tMax,
                              HitRecord* hits) const;
  // The planes against the packet's rays in `live`, |V| rays to a vector, the same arithmetic
  // as Plane::intersect lane by lane: each ray's nearest plane hit before tMax[i] shrinks
  // tMax[i] and sets plane[i] to the plane's index (unless plane is null: shadow rays need not
  // know which). Returns the rays that hit a plane.
  template <class V>
  uint32_t planeLanes(const RayPacket8& packet, uint32_t live, float* tMax, int* plane) const;
  // Whether a plane lies on the ray within (tMin, tMax): the shadow test's planes.
  bool blockedByPlane(const Ray& ray) const;
  // Whether the leaf entries [first, first + count) are all spheres.
  bool onlySpheres(uint32_t first, uint32_t count) const;
  // The watertight test's per-ray shear, or nothing computed when another test is chosen.
  WatertightRay shearFor(const Ray& ray) const {
    return triangleTest_ == TriangleTest::Watertight ? WatertightRay(ray.direction)
                                                     : WatertightRay();
  }
  // A triangle by the index its hits carry: into triangles_, or pack · 4 + lane once packed.
  Triangle triangle(uint32_t index) const;
  // The mesh holding the triangle numbered `number` over all meshes.
  uint32_t meshOfTriangle(uint32_t number) const {
    const auto next = std::upper_bound(
        meshes_.begin(), meshes_.end(), number,
        [](uint32_t n, const MeshShading& mesh) { return n < mesh.firstTriangle; });
    return static_cast<uint32_t>(next - meshes_.begin()) - 1;
  }
  // The build's parts (SceneGeometry.cpp). Fills the leaf entries and the primitive arrays in
  // the BVH's leaf order from the gathered shape parts (kindFirst[k]: the number of kind k's
  // first part) and, unless packed, the triangles in input order.
  void placeInLeafOrder(const GeometryInput& parts,
                        const std::array<uint32_t, kShapeKindCount + 1>& kindFirst,
                        const std::vector<Triangle>& triangles, bool packed);
  // Fills stats_ once everything is built (in: what the build was given).
  void recordStats(const GeometryInput& in);
  // Fills packs_ with the triangles the leaf entries point at (on `threads` threads) and
  // relabels the wide BVH's leaves to (first pack, pack count). accel/LeafPacks.cpp.
  void buildTrianglePacks(const std::vector<MeshInput>& meshes, unsigned threads);

  TriangleTest triangleTest_;
  Traversal traversal_;
  const GeometryKernels* kernels_;
  std::vector<Triangle> triangles_;  // in BVH order; empty once packs hold the triangles
  // Each kind of geometry/ShapeKinds.h in BVH order (a cone's parts as cones) with its caustic
  // bits: spheres_, spheresCaustic_, cones_, conesCaustic_, ...
#define PRISM_SHAPE_ARRAYS(Shape, plural) \
  std::vector<Shape> plural##_;           \
  std::vector<uint8_t> plural##Caustic_;
  PRISM_SHAPE_KINDS(PRISM_SHAPE_ARRAYS)
#undef PRISM_SHAPE_ARRAYS
  std::vector<Plane> planes_;
  bool testTreeBoxFirst_ = false;  // occluded() asks WideBvh::entersTree before the walk
  std::vector<MeshShading> meshes_;
  std::vector<uint8_t> planeCaustic_;  // parallel to planes_
  Aabb bounds_;
  std::vector<uint32_t> leafRefs_;  // PrimitiveRef per BVH leaf entry (packs: only if mixed)
  Bvh bvh_;                         // empty once the wide BVH is collapsed from it
  WideBvh wideBvh_;
  std::vector<LeafPack> packs_;
  bool packed_ = false;  // the wide walk's leaves point at packs (or are packless)
  SceneBuildStats stats_;
};

}  // namespace prism
