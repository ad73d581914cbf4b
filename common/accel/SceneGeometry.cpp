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

  // Gather every bounded primitive in input order, then reorder by BVH leaf order so a leaf's
  // primitives sit together in memory. Packed triangles are not gathered: the packs read them
  // from the meshes.
  std::vector<Triangle> triangles;
  std::vector<Cone> cones;
  std::vector<Aabb> bounds;
  std::vector<uint32_t> refs;
  std::vector<uint8_t> coneCaustic;
  const size_t bounded = in.spheres.size() + in.cones.size() + triangleCount;
  if (!packed) reserveOnHugePages(triangles, triangleCount);
  reserveOnHugePages(bounds, bounded);
  reserveOnHugePages(refs, bounded);
  for (uint32_t i = 0; i < in.spheres.size(); ++i) {
    refs.push_back(PrimitiveRef::make(PrimitiveKind::Sphere, i));
    bounds.push_back(in.spheres[i].bounds());
  }
  for (size_t c = 0; c < in.cones.size(); ++c) {
    for (const Cone& part : splitForBvh(in.cones[c])) {
      refs.push_back(PrimitiveRef::make(PrimitiveKind::Cone, cones.size()));
      cones.push_back(part);
      bounds.push_back(part.bounds());
      coneCaustic.push_back(in.coneCaustic[c]);
    }
  }
  uint32_t triangleNumber = 0;  // over all meshes, in order
  for (uint32_t m = 0; m < in.meshes.size(); ++m) {
    const MeshInput& mesh = in.meshes[m];
    MeshShading shading{{}, {}, mesh.material, mesh.caustic, triangleNumber};
    reserveOnHugePages(shading.normals, mesh.normals.size());
    shading.normals.assign(mesh.normals.begin(), mesh.normals.end());
    reserveOnHugePages(shading.indices, mesh.indices.size());
    shading.indices.assign(mesh.indices.begin(), mesh.indices.end());
    meshes_.push_back(std::move(shading));
    const uint32_t faces = static_cast<uint32_t>(mesh.indices.size() / 3);
    const size_t firstEntry = refs.size();
    refs.resize(firstEntry + faces);
    bounds.resize(firstEntry + faces);
    if (!packed) triangles.resize(size_t{triangleNumber} + faces);
    forChunks(faces, 16384, gatherThreads, [&](uint64_t begin, uint64_t end) {
      for (uint32_t f = static_cast<uint32_t>(begin); f < end; ++f) {
        const Triangle tri = mesh.triangle(m, f);
        refs[firstEntry + f] = PrimitiveRef::make(PrimitiveKind::Triangle, triangleNumber + f);
        bounds[firstEntry + f] = tri.bounds();
        if (!packed) triangles[size_t{triangleNumber} + f] = tri;
      }
    });
    triangleNumber += faces;
  }
  for (const Aabb& b : bounds) bounds_.extend(b);

  buildOptions.blockedFrom = static_cast<uint32_t>(in.spheres.size() + cones.size());
  bvh_.build(bounds, buildOptions);
  std::vector<Aabb>().swap(bounds);
  // Packed triangles go straight from the meshes into their packs: their leaf entries keep the
  // triangle's number.
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
  std::vector<uint32_t>().swap(refs);

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
