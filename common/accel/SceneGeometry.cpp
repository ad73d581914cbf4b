#include "accel/SceneGeometry.h"

#include <utility>

#include "accel/PrimitiveRef.h"
#include "geometry/ConeSegments.h"
#include "util/HugePages.h"
#include "util/Parallel.h"

namespace prism {
namespace {

// Below this many triangles a scene is gathered and packed on one thread: starting another
// costs more than it saves.
constexpr uint64_t kParallelGatherMinTriangles = 32768;

}  // namespace

SceneGeometry::SceneGeometry(GeometryInput in)
    : triangleTest_(in.triangleTest),
      traversal_(in.traversal),
      kernels_(&geometryKernels(resolveInstructionSet(in.instructionSet))),
      planes_(std::move(in.planes)),
      planeCaustic_(std::move(in.planeCaustic)) {
  // The SIMD walk tests four triangles for the price of one: let the SAH fill packs. Spheres and
  // cones, gathered before the triangles, are tested one at a time.
  const bool packed =
      traversal_ == Traversal::WideSimd && triangleTest_ != TriangleTest::PlaneThenInside;
  BvhBuildOptions buildOptions;
  buildOptions.primitiveBlock = packed ? TrianglePack4::kWidth : 1;
  const size_t triangleCount = in.triangleCount();
  const unsigned gatherThreads =
      triangleCount >= kParallelGatherMinTriangles ? buildOptions.threads : 1;

  // Bounded primitives are numbered in input order: spheres, cone parts, then every mesh's
  // triangles. The BVH asks for their boxes by number, so no array of boxes is kept; after the
  // build they are reordered by leaf so a leaf's primitives sit together in memory. Packed
  // triangles are not gathered: the packs read them from the meshes.
  std::vector<Cone> cones;
  std::vector<uint8_t> coneCaustic;
  for (size_t c = 0; c < in.cones.size(); ++c) {
    for (const Cone& part : splitForBvh(in.cones[c])) {
      cones.push_back(part);
      coneCaustic.push_back(in.coneCaustic[c]);
    }
  }
  uint32_t triangleNumber = 0;  // over all meshes, in order
  for (const MeshInput& mesh : in.meshes) {
    MeshShading shading{{}, {}, mesh.material, mesh.caustic, triangleNumber};
    reserveOnHugePages(shading.normals, mesh.normals.size());
    shading.normals.assign(mesh.normals.begin(), mesh.normals.end());
    reserveOnHugePages(shading.indices, mesh.indices.size());
    shading.indices.assign(mesh.indices.begin(), mesh.indices.end());
    meshes_.push_back(std::move(shading));
    triangleNumber += static_cast<uint32_t>(mesh.indices.size() / 3);
  }
  const uint32_t sphereCount = static_cast<uint32_t>(in.spheres.size());
  const uint32_t firstTriangle = sphereCount + static_cast<uint32_t>(cones.size());
  const auto refOf = [&](uint32_t primitive) {
    if (primitive < sphereCount) return PrimitiveRef::make(PrimitiveKind::Sphere, primitive);
    if (primitive < firstTriangle) {
      return PrimitiveRef::make(PrimitiveKind::Cone, primitive - sphereCount);
    }
    return PrimitiveRef::make(PrimitiveKind::Triangle, primitive - firstTriangle);
  };
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
        if (primitive < sphereCount) return in.spheres[primitive].bounds();
        if (primitive < firstTriangle) return cones[primitive - sphereCount].bounds();
        const uint32_t number = primitive - firstTriangle;
        return packed ? triangleNumbered(number).bounds() : triangles[number].bounds();
      },
      buildOptions);
  bounds_ = bvh_.bounds();  // the root's box: every primitive's, extended in input order
  // Packed triangles go straight from the meshes into their packs: their leaf entries keep the
  // triangle's number.
  reserveOnHugePages(leafRefs_, bounded);
  if (!packed) reserveOnHugePages(triangles_, triangles.size());
  for (uint32_t original : bvh_.primitiveOrder()) {
    const uint32_t ref = refOf(original);
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
        spheres_.push_back(in.spheres[index]);
        sphereCaustic_.push_back(in.sphereCaustic[index]);
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

  stats_.bvh = bvh_.stats();
  if (traversal_ != Traversal::BinaryScalar) {
    wideBvh_.build(bvh_);
    bvh_ = Bvh();  // the wide walk never reads the binary tree again
    stats_.binaryBvhReleased = true;
  }
  if (packed) {
    buildTrianglePacks(in.meshes, gatherThreads);
    packed_ = true;
    // The packs hold every triangle's vertices and source: unless spheres or cones share the
    // leaves, the leaf entries are no longer read.
    if (spheres_.empty() && cones_.empty()) std::vector<uint32_t>().swap(leafRefs_);
  }

  testTreeBoxFirst_ = !planes_.empty() && traversal_ != Traversal::BinaryScalar;

  stats_.spheres = spheres_.size();
  stats_.planes = planes_.size();
  stats_.cones = in.cones.size();
  stats_.coneSegments = cones_.size();
  stats_.triangles = triangleCount;
  stats_.wideBvh = wideBvh_.stats();
  stats_.packBytes = packs_.size() * sizeof(LeafPack);
  stats_.geometryBytes = triangles_.capacity() * sizeof(Triangle) +
                         spheres_.size() * sizeof(Sphere) + cones_.size() * sizeof(Cone) +
                         planes_.size() * sizeof(Plane) + leafRefs_.capacity() * sizeof(uint32_t);
  for (const MeshShading& m : meshes_) {
    stats_.geometryBytes += m.normals.size() * sizeof(Vec3) + m.indices.size() * sizeof(uint32_t);
  }
}

void SceneGeometry::useInstructionSet(InstructionSet isa) {
  kernels_ = &geometryKernels(resolveInstructionSet(isa));
}

}  // namespace prism
