// The field lists of a built SceneGeometry (wire/Fields.h says how a list reads): the primitives
// in BVH order, the BVH (binary or wide), the triangle packs and the meshes' shading data, so
// rank 0 can broadcast the geometry it built and a slave walks the very same structure instead
// of building its own (docs/distributed.md, "One build per job"). The build is deterministic, so
// the slave's image is the one it would have rendered from its own build.
//
// The geometry's members are private: these lists name them as friends of the classes. A list
// written by hand cannot break the build when a member is added, so each class's size is pinned
// below: a new member changes it and points here.
//
// What a reader cannot trust is checked before any walk runs (Fields<SceneGeometry>::check):
// every child, leaf, pack lane and primitive reference points inside its array, interior nodes
// point forward (no cycles) and no deeper than the walks' stacks allow, parallel arrays agree,
// and the mesh numbering is consistent. checkGeometryFitsScene then checks the geometry against
// the description it was built from (counts, material ids).
#pragma once

#include "accel/SceneGeometry.h"
#include "scene/SceneDescription.h"
#include "wire/Fields.h"

namespace prism {

// The walk a geometry was built for, as wire/WireEnums.h says of the other enumerations; here,
// and found by argument-dependent lookup, so that the rest of the wire does not reach the
// acceleration structures.
inline bool isKnown(Traversal t) {
  switch (t) {
    case Traversal::WideSimd:
    case Traversal::WideScalarLeaves:
    case Traversal::BinaryScalar:
      return true;
  }
  return false;
}
inline const char* enumName(Traversal) {
  return "BVH traversal";
}

}  // namespace prism

namespace prism::wire {

template <>
struct Fields<Aabb> {
  PRISM_WIRE_FIELDS(lower, upper)
};

template <>
struct Fields<Triangle> {
  PRISM_WIRE_FIELDS(v0, v1, v2, mesh, face)
  static constexpr bool kMemoryIsWireForm = sizeof(Triangle) == 44;
};

template <>
struct Fields<Plane> {
  PRISM_WIRE_FIELDS(normal, offset, material)
  static constexpr bool kMemoryIsWireForm = sizeof(Plane) == 20;
};

template <>
struct Fields<BvhNode> {
  PRISM_WIRE_FIELDS(bounds, offset, count, splitAxis, padding)
  static constexpr bool kMemoryIsWireForm = sizeof(BvhNode) == 32;
};

template <>
struct Fields<BvhBuildStats> {
  PRISM_WIRE_FIELDS(seconds, nodeCount, leafCount, maxDepth, memoryBytes)
};

template <>
struct Fields<Bvh> {
  static void fields(auto& self, auto&& visit) { visit(self.nodes_, self.order_, self.stats_); }
};

template <>
struct Fields<WideBvhNode> {
  PRISM_WIRE_FIELDS(bounds, child, count, unused)
  static constexpr bool kMemoryIsWireForm = sizeof(WideBvhNode) == 256;
};

template <>
struct Fields<WideBvhStats> {
  PRISM_WIRE_FIELDS(nodeCount, memoryBytes, seconds)
};

template <>
struct Fields<WideBvh> {
  static void fields(auto& self, auto&& visit) {
    visit(self.nodes_, self.rootBounds_, self.stats_);
  }
};

template <>
struct Fields<TrianglePack4> {
  PRISM_WIRE_FIELDS(v0, v1, v2, triangle)
};

template <>
struct Fields<SceneGeometry::LeafPack> {
  PRISM_WIRE_FIELDS(triangles, leafFirst, leafCount, hasOtherKinds, unused)
  // Copied in one go; the flag's byte is checked with the rest (Fields<SceneGeometry>::check).
  static constexpr bool kMemoryIsWireForm = sizeof(SceneGeometry::LeafPack) == 176;
};

template <>
struct Fields<SceneGeometry::MeshShading> {
  PRISM_WIRE_FIELDS(normals, indices, material, caustic, firstTriangle, uvs, colors, faceMaterials)
};

template <>
struct Fields<SceneBuildStats> {
  PRISM_WIRE_FIELDS(PRISM_SHAPE_KINDS(PRISM_SHAPE_PLURAL_COMMA) planes, triangles, bvh,
                    binaryBvhReleased, wideBvh, packBytes, geometryBytes)
};

template <>
struct Fields<SceneGeometry> {
  static void fields(auto& self, auto&& visit) {
#define PRISM_SHAPE_MEMBERS(Shape, plural) self.plural##_, self.plural##Caustic_,
    visit(self.triangleTest_, self.traversal_, self.triangles_,
          PRISM_SHAPE_KINDS(PRISM_SHAPE_MEMBERS) self.planes_, self.testTreeBoxFirst_, self.meshes_,
          self.planeCaustic_, self.bounds_, self.leafRefs_, self.bvh_, self.wideBvh_, self.packs_,
          self.packed_, self.stats_);
#undef PRISM_SHAPE_MEMBERS
  }
  // Everything a walk or a surface lookup would index with (see the top of this file). Throws
  // WireError naming the first fault.
  static void check(const SceneGeometry& geometry);
  static void checkFitsScene(const SceneGeometry& geometry, const SceneDescription& scene);
  // The wire form's size, near enough to reserve it at once (hundreds of megabytes).
  static size_t wireBytes(const SceneGeometry& geometry);
};

// Whether the geometry is the description's: as many shapes of each kind, planes and triangles, and
// every material id within the description's materials. Throws WireError.
void checkGeometryFitsScene(const SceneGeometry& geometry, const SceneDescription& scene);

}  // namespace prism::wire
