// The triangle packs of the wide walk: each leaf's triangles four to a pack, read straight from
// the meshes, and the wide BVH's leaves relabelled to point at them.
#include <stdexcept>
#include <utility>

#include "accel/PrimitiveRef.h"
#include "accel/SceneGeometry.h"
#include "util/HugePages.h"
#include "util/Parallel.h"

namespace prism {

void SceneGeometry::buildTrianglePacks(const std::vector<MeshInput>& meshes, unsigned threads) {
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
  reserveOnHugePages(leaves, stats_.bvh.leafCount);  // grown by doubling it faulted in 4 KiB pages
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
    const uint32_t m = meshOfTriangle(number);
    return meshes[m].triangle(m, number - meshes_[m].firstTriangle);
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

}  // namespace prism
