#include "accel/SceneGeometry.h"

#include <array>
#include <stdexcept>
#include <utility>

#include "accel/PrimitiveRef.h"
#include "util/HugePages.h"
#include "util/Parallel.h"

namespace prism {
namespace {

// Below this many triangles a scene is gathered and packed on one thread: starting another
// costs more than it saves.
constexpr uint64_t kParallelGatherMinTriangles = 32768;

// The shapes as the BVH takes them (a slanted cone in parts, geometry/ShapeKinds.h), with
// their caustic bits, and the number of each kind's first part: the BVH numbers the kinds'
// parts in the list's order.
struct ShapeParts {
  GeometryInput parts;
  std::array<uint32_t, kShapeKindCount + 1> kindFirst{};
};

// The BVH's entry for bounded primitive number `primitive`: the shape parts of each kind in the
// list's order (kindFirst[k]: the first of kind k), then every mesh's triangles.
uint32_t primitiveRef(const std::array<uint32_t, kShapeKindCount + 1>& kindFirst,
                      uint32_t primitive) {
  const uint32_t firstTriangle = kindFirst[kShapeKindCount];
  if (primitive >= firstTriangle) {
    return PrimitiveRef::make(PrimitiveKind::Triangle, primitive - firstTriangle);
  }
  size_t k = 0;
  while (primitive >= kindFirst[k + 1]) ++k;
  return PrimitiveRef::make(shapeKind(k), primitive - kindFirst[k]);
}

// The box of the shape part `ref` names among the gathered parts.
Aabb partBounds(const GeometryInput& parts, uint32_t ref) {
  const uint32_t index = PrimitiveRef::index(ref);
  switch (PrimitiveRef::kind(ref)) {
#define PRISM_PART_BOUNDS(Shape, plural) \
  case PrimitiveKind::Shape:             \
    return parts.plural[index].bounds();
    PRISM_SHAPE_KINDS(PRISM_PART_BOUNDS)
#undef PRISM_PART_BOUNDS
    case PrimitiveKind::Triangle:
    case PrimitiveKind::Plane:
      break;
  }
  return Aabb();
}

// Each mesh's shading data, numbered by its first triangle over all meshes in order.
std::vector<SceneGeometry::MeshShading> meshShading(const std::vector<MeshInput>& meshes) {
  std::vector<SceneGeometry::MeshShading> out;
  uint32_t triangleNumber = 0;
  for (const MeshInput& mesh : meshes) {
    SceneGeometry::MeshShading shading{{}, {}, mesh.material, mesh.caustic, triangleNumber, {},
                                       {}, {}};
    reserveOnHugePages(shading.normals, mesh.normals.size());
    shading.normals.assign(mesh.normals.begin(), mesh.normals.end());
    reserveOnHugePages(shading.indices, mesh.indices.size());
    shading.indices.assign(mesh.indices.begin(), mesh.indices.end());
    shading.uvs.assign(mesh.uvs.begin(), mesh.uvs.end());
    shading.colors.assign(mesh.colors.begin(), mesh.colors.end());
    shading.faceMaterials.assign(mesh.faceMaterials.begin(), mesh.faceMaterials.end());
    out.push_back(std::move(shading));
    triangleNumber += static_cast<uint32_t>(mesh.indices.size() / 3);
  }
  return out;
}

ShapeParts gatherShapeParts(const GeometryInput& in) {
  ShapeParts out;
  size_t kind = 0;
  const auto gather = [&](const auto& shapes, const std::vector<uint8_t>& caustic, auto& parts,
                          std::vector<uint8_t>& partsCaustic) {
    for (size_t i = 0; i < shapes.size(); ++i) {
      if constexpr (requires { bvhParts(shapes[i]); }) {
        for (const auto& part : bvhParts(shapes[i])) {
          parts.push_back(part);
          partsCaustic.push_back(caustic[i]);
        }
      } else {  // a kind the BVH takes whole: no vector of one per shape
        parts.push_back(shapes[i]);
        partsCaustic.push_back(caustic[i]);
      }
    }
    if (parts.size() > PrimitiveRef::kMaxIndex) {
      throw std::length_error("too many shapes of one kind for the BVH's entries");
    }
    out.kindFirst[kind + 1] = out.kindFirst[kind] + static_cast<uint32_t>(parts.size());
    ++kind;
  };
#define PRISM_GATHER_PARTS(Shape, plural) \
  gather(in.plural, in.plural##Caustic, out.parts.plural, out.parts.plural##Caustic);
  PRISM_SHAPE_KINDS(PRISM_GATHER_PARTS)
#undef PRISM_GATHER_PARTS
  return out;
}

}  // namespace

SceneGeometry::SceneGeometry(GeometryInput in)
    : triangleTest_(in.triangleTest),
      traversal_(in.traversal),
      kernels_(&geometryKernels(resolveInstructionSet(in.instructionSet))),
      planes_(std::move(in.planes)),
      planeCaustic_(std::move(in.planeCaustic)) {
  // The SIMD walk tests four triangles for the price of one: let the SAH fill packs. The shapes,
  // gathered before the triangles, are tested one at a time.
  const bool packed =
      traversal_ == Traversal::WideSimd && triangleTest_ != TriangleTest::PlaneThenInside;
  BvhBuildOptions buildOptions;
  buildOptions.primitiveBlock = packed ? TrianglePack4::kWidth : 1;
  const size_t triangleCount = in.triangleCount();
  const unsigned gatherThreads =
      triangleCount >= kParallelGatherMinTriangles ? buildOptions.threads : 1;

  // Bounded primitives are numbered in input order: the parts of each kind of
  // geometry/ShapeKinds.h in the list's order, then every mesh's triangles. The BVH asks for
  // their boxes by number, so no array of boxes is kept; after the build they are reordered by
  // leaf so a leaf's primitives sit together in memory. Packed triangles are not gathered: the
  // packs read them from the meshes.
  const ShapeParts shapes = gatherShapeParts(in);
  const GeometryInput& parts = shapes.parts;
  const std::array<uint32_t, kShapeKindCount + 1>& kindFirst = shapes.kindFirst;
  meshes_ = meshShading(in.meshes);
  const uint32_t firstTriangle = kindFirst[kShapeKindCount];
  if (triangleCount > kMaxTriangles) {
    throw std::length_error("too many triangles for the BVH's entries");
  }
  const auto triangleNumbered = [&](uint32_t number) {
    const uint32_t m = meshOfTriangle(number);
    return in.meshes[m].triangle(m, number - meshes_[m].firstTriangle);
  };
  std::vector<Triangle> triangles;  // in input order, for the unpacked walks
  if (!packed) {
    reserveOnHugePages(triangles, triangleCount);
    triangles.resize(triangleCount);
    forChunks(triangleCount, 16384, gatherThreads, [&](uint64_t begin, uint64_t end) {
      for (uint64_t t = begin; t < end; ++t) {
        triangles[t] = triangleNumbered(static_cast<uint32_t>(t));
      }
    });
  }

  buildOptions.blockedFrom = firstTriangle;
  const uint32_t bounded = firstTriangle + static_cast<uint32_t>(triangleCount);
  bvh_.build(
      bounded,
      [&](uint32_t primitive) {
        if (primitive >= firstTriangle) {
          const uint32_t number = primitive - firstTriangle;
          return packed ? triangleNumbered(number).bounds() : triangles[number].bounds();
        }
        return partBounds(parts, primitiveRef(kindFirst, primitive));
      },
      buildOptions);
  bounds_ = bvh_.bounds();  // the root's box: every primitive's, extended in input order
  placeInLeafOrder(parts, kindFirst, triangles, packed);
  // The gathered copies are done with: free them before the wide BVH and its packs are built, so
  // the build's peak stays within scene/MeshBudget.h's estimate.
  std::vector<Triangle>().swap(triangles);

  stats_.bvh = bvh_.stats();
  if (traversal_ != Traversal::BinaryScalar) {
    wideBvh_.build(bvh_);
    bvh_ = Bvh();  // the wide walk never reads the binary tree again
    stats_.binaryBvhReleased = true;
  }
  if (packed) {
    buildTrianglePacks(in.meshes, gatherThreads);
    packed_ = true;
    // The packs hold every triangle's vertices and source: unless shapes share the leaves, the
    // leaf entries are no longer read.
    if (firstTriangle == 0) std::vector<uint32_t>().swap(leafRefs_);
  }

  testTreeBoxFirst_ = !planes_.empty() && traversal_ != Traversal::BinaryScalar;

  recordStats(in);
}

void SceneGeometry::placeInLeafOrder(const GeometryInput& parts,
                                     const std::array<uint32_t, kShapeKindCount + 1>& kindFirst,
                                     const std::vector<Triangle>& triangles, bool packed) {
  // Packed triangles go straight from the meshes into their packs: their leaf entries keep the
  // triangle's number.
  reserveOnHugePages(leafRefs_, bvh_.primitiveOrder().size());  // one per bounded primitive
  if (!packed) reserveOnHugePages(triangles_, triangles.size());
  for (uint32_t original : bvh_.primitiveOrder()) {
    const uint32_t ref = primitiveRef(kindFirst, original);
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
#define PRISM_REORDER_PART(Shape, plural)                                                      \
  case PrimitiveKind::Shape:                                                                   \
    leafRefs_.push_back(PrimitiveRef::make(PrimitiveKind::Shape, uint32_t(plural##_.size()))); \
    plural##_.push_back(parts.plural[index]);                                                  \
    plural##Caustic_.push_back(parts.plural##Caustic[index]);                                  \
    break;
        PRISM_SHAPE_KINDS(PRISM_REORDER_PART)
#undef PRISM_REORDER_PART
      case PrimitiveKind::Plane:
        break;  // planes are unbounded and never enter the BVH
    }
  }
}

void SceneGeometry::recordStats(const GeometryInput& in) {
  stats_.planes = planes_.size();
  stats_.triangles = in.triangleCount();
  stats_.wideBvh = wideBvh_.stats();
  stats_.packBytes = packs_.size() * sizeof(LeafPack);
  stats_.geometryBytes = triangles_.capacity() * sizeof(Triangle) + planes_.size() * sizeof(Plane) +
                         leafRefs_.capacity() * sizeof(uint32_t);
#define PRISM_SHAPE_STATS(Shape, plural)                \
  stats_.plural = {in.plural.size(), plural##_.size()}; \
  stats_.geometryBytes += plural##_.size() * sizeof(Shape);
  PRISM_SHAPE_KINDS(PRISM_SHAPE_STATS)
#undef PRISM_SHAPE_STATS
  for (const MeshShading& m : meshes_) {
    stats_.geometryBytes += m.normals.size() * sizeof(Vec3) + m.indices.size() * sizeof(uint32_t) +
                            m.uvs.size() * sizeof(Vec2) + m.colors.size() * sizeof(Color) +
                            m.faceMaterials.size() * sizeof(MaterialId);
  }
}

void SceneGeometry::useInstructionSet(InstructionSet isa) {
  kernels_ = &geometryKernels(resolveInstructionSet(isa));
}

}  // namespace prism
