#include "wire/GeometryCodec.h"

#include <cstring>
#include <string>
#include <vector>

#include "accel/PrimitiveRef.h"
#include "wire/ByteBuffer.h"

namespace prism::wire {
namespace {

[[noreturn]] void fault(const std::string& what) {
  throw WireError("geometry: " + what);
}

std::string at(const char* array, size_t index) {
  return std::string(array) + "[" + std::to_string(index) + "]";
}

// The binary walk's stack holds one entry a level (Bvh::traverse), the wide walks' seven.
constexpr size_t kMaxTreeDepth = 2 * Bvh::kMaxDepth;

bool isUnusedSlot(const WideBvhNode& node, int slot) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  if (node.count[slot] != 0 || node.child[slot] != 0) return false;
  for (int a = 0; a < 3; ++a) {
    if (node.bounds[2 * a][slot] != kInf || node.bounds[2 * a + 1][slot] != -kInf) return false;
  }
  return true;
}

// Meshes: numbered in order from 0, three indices a face, normals (if any) for every index;
// their faces add up to the geometry's triangles.
void checkMeshes(const std::vector<SceneGeometry::MeshShading>& meshes, size_t triangleCount) {
  size_t nextTriangle = 0;
  for (size_t m = 0; m < meshes.size(); ++m) {
    const SceneGeometry::MeshShading& mesh = meshes[m];
    if (mesh.firstTriangle != nextTriangle) fault(at("mesh", m) + " does not follow the last");
    if (mesh.indices.size() % 3 != 0) fault(at("mesh", m) + " has a partial face");
    // Every per-vertex array the surface reads by a face's indices covers them.
    for (const size_t vertices : {mesh.normals.size(), mesh.uvs.size(), mesh.colors.size()}) {
      if (vertices == 0) continue;
      for (size_t i = 0; i < mesh.indices.size(); ++i) {
        if (mesh.indices[i] >= vertices) fault(at("mesh", m) + " index past its vertex data");
      }
    }
    if (!mesh.faceMaterials.empty() && mesh.faceMaterials.size() != mesh.indices.size() / 3) {
      fault(at("mesh", m) + " has face materials not one per face");
    }
    nextTriangle += mesh.indices.size() / 3;
  }
  if (nextTriangle != triangleCount) fault("the meshes' faces do not add up to the triangles");
}

// The listed triangles (the unpacked walks'): each names a face of its mesh.
void checkTriangles(const std::vector<Triangle>& triangles,
                    const std::vector<SceneGeometry::MeshShading>& meshes, size_t triangleCount) {
  for (size_t i = 0; i < triangles.size(); ++i) {
    const Triangle& tri = triangles[i];
    if (tri.mesh >= meshes.size() ||
        size_t{meshes[tri.mesh].firstTriangle} + tri.face >= triangleCount ||
        3 * (size_t{tri.face} + 1) > meshes[tri.mesh].indices.size()) {
      fault(at("triangle", i) + " names no mesh face");
    }
  }
}

// Packs: every lane's triangle number within the triangles, a leaf's other entries within the
// leaf entries, flags that are bools.
void checkPacks(const std::vector<SceneGeometry::LeafPack>& packs, size_t leafEntries,
                size_t triangleCount) {
  for (size_t p = 0; p < packs.size(); ++p) {
    const SceneGeometry::LeafPack& pack = packs[p];
    uint8_t flag = 0;
    std::memcpy(&flag, &pack.hasOtherKinds, 1);
    if (flag > 1) fault(at("pack", p) + " has a flag of " + std::to_string(flag));
    if (flag == 1 && size_t{pack.leafFirst} + pack.leafCount > leafEntries) {
      fault(at("pack", p) + " points past the leaf entries");
    }
    for (uint32_t number : pack.triangles.triangle) {
      if (number >= triangleCount) fault(at("pack", p) + " names a triangle past the meshes");
    }
  }
}

// Binary tree: children after their parent, within the nodes; leaves within the entries.
void checkBinaryTree(const std::vector<BvhNode>& nodes, size_t leafEntries) {
  std::vector<uint8_t> depth(nodes.size(), 0);
  for (size_t i = 0; i < nodes.size(); ++i) {
    const BvhNode& node = nodes[i];
    if (node.isLeaf()) {
      if (size_t{node.offset} + node.count > leafEntries) {
        fault(at("BVH node", i) + " points past the leaf entries");
      }
      continue;
    }
    if (i + 1 >= nodes.size() || node.offset <= i || node.offset >= nodes.size()) {
      fault(at("BVH node", i) + " has a child outside the tree");
    }
    if (depth[i] + 1u > kMaxTreeDepth) fault(at("BVH node", i) + " lies too deep");
    depth[i + 1] = depth[node.offset] = static_cast<uint8_t>(depth[i] + 1);
  }
}

// Wide tree: the same, per slot; unused slots exactly as the build leaves them (no ray enters
// them). A leaf slot points into the packs, or (packless, or no packed walk) the leaf entries.
void checkWideTree(const std::vector<WideBvhNode>& nodes, bool packed, size_t packCount,
                   size_t leafEntries) {
  std::vector<uint8_t> depth(nodes.size(), 0);
  for (size_t i = 0; i < nodes.size(); ++i) {
    const WideBvhNode& node = nodes[i];
    for (int s = 0; s < WideBvhNode::kWidth; ++s) {
      const uint32_t child = node.child[s];
      const uint32_t count = node.count[s];
      if (count == 0) {
        if (isUnusedSlot(node, s)) continue;
        if (child <= i || child >= nodes.size()) {
          fault(at("wide node", i) + " has a child outside the tree");
        }
        if (depth[i] + 1u > kMaxTreeDepth) fault(at("wide node", i) + " lies too deep");
        depth[child] = static_cast<uint8_t>(depth[i] + 1);
        continue;
      }
      const bool packless = packed && (child & SceneGeometry::kPacklessLeaf) != 0;
      const size_t first = packless ? (child & ~SceneGeometry::kPacklessLeaf) : child;
      const size_t end = packed && !packless ? packCount : leafEntries;
      if (first + count > end) fault(at("wide node", i) + " has a leaf past its array");
    }
  }
}

}  // namespace

// Friends of SceneGeometry (and so of its private parts) by being this specialisation's member.
void Fields<SceneGeometry>::check(const SceneGeometry& g) {
  static_assert(sizeof(SceneGeometry) == 656,
                "a member was added to SceneGeometry: list it (kernels_ is not sent)");
  const size_t triangleCount = g.stats_.triangles;
  if (g.planeCaustic_.size() != g.planes_.size()) fault("caustic flags do not match the planes");
  if (g.stats_.planes != g.planes_.size()) fault("counts do not match the planes");
#define PRISM_CHECK_SHAPE_ARRAYS(Shape, plural)          \
  if (g.plural##Caustic_.size() != g.plural##_.size()) { \
    fault("caustic flags do not match the " #plural);    \
  }                                                      \
  if (g.stats_.plural.bvhParts != g.plural##_.size()) {  \
    fault("counts do not match the " #plural);           \
  }
  PRISM_SHAPE_KINDS(PRISM_CHECK_SHAPE_ARRAYS)
#undef PRISM_CHECK_SHAPE_ARRAYS

  checkMeshes(g.meshes_, triangleCount);
  if (g.packed_ ? !g.triangles_.empty() : g.triangles_.size() != triangleCount) {
    fault("the listed triangles do not match the meshes");
  }
  checkTriangles(g.triangles_, g.meshes_, triangleCount);

  // Leaf entries: a known kind, an index within its array.
  for (size_t i = 0; i < g.leafRefs_.size(); ++i) {
    const uint32_t ref = g.leafRefs_[i];
    const uint32_t index = PrimitiveRef::index(ref);
    bool inside = false;
    switch (PrimitiveRef::kind(ref)) {
      case PrimitiveKind::Triangle:
        inside = index < (g.packed_ ? triangleCount : g.triangles_.size());
        break;
#define PRISM_SHAPE_INSIDE(Shape, plural) \
  case PrimitiveKind::Shape:              \
    inside = index < g.plural##_.size();  \
    break;
        PRISM_SHAPE_KINDS(PRISM_SHAPE_INSIDE)
#undef PRISM_SHAPE_INSIDE
      case PrimitiveKind::Plane:
        break;  // planes never enter the BVH
    }
    if (!inside) fault(at("leaf entry", i) + " points nowhere");
  }

  checkPacks(g.packs_, g.leafRefs_.size(), triangleCount);
  if (!g.packed_ && !g.packs_.empty()) fault("packs without a packed walk");

  const std::vector<BvhNode>& bin = g.bvh_.nodes_;
  checkBinaryTree(bin, g.leafRefs_.size());
  if (g.traversal_ == Traversal::BinaryScalar && bin.empty() && !g.leafRefs_.empty()) {
    fault("entries without a tree");
  }

  const std::vector<WideBvhNode>& wide = g.wideBvh_.nodes_;
  checkWideTree(wide, g.packed_, g.packs_.size(), g.leafRefs_.size());
  if (g.traversal_ != Traversal::BinaryScalar && wide.empty() && !g.leafRefs_.empty()) {
    fault("entries without a tree");
  }
  if (g.traversal_ != Traversal::BinaryScalar && !bin.empty()) {
    fault("a binary tree beside the wide one");
  }
  if (g.traversal_ == Traversal::BinaryScalar && (!wide.empty() || g.packed_)) {
    fault("a wide tree beside the binary one");
  }
  uint8_t flag = 0;
  for (const bool* b : {&g.packed_, &g.testTreeBoxFirst_, &g.stats_.binaryBvhReleased}) {
    std::memcpy(&flag, b, 1);
    if (flag > 1) fault("a flag of " + std::to_string(flag));
  }
}

void Fields<SceneGeometry>::checkFitsScene(const SceneGeometry& g, const SceneDescription& scene) {
  const SceneBuildStats& stats = g.stats_;
  size_t triangles = 0;
  for (const MeshDesc& mesh : scene.meshes) triangles += mesh.indices.size() / 3;
  bool sameCounts = stats.planes == scene.planes.size() &&
                    g.meshes_.size() == scene.meshes.size() && stats.triangles == triangles;
  std::string counts = std::to_string(stats.triangles) + " triangles, ";
#define PRISM_COUNT_SHAPES(Shape, plural)                               \
  sameCounts = sameCounts && stats.plural.count == scene.plural.size(); \
  counts += std::to_string(stats.plural.count) + " " #plural ", ";
  PRISM_SHAPE_KINDS(PRISM_COUNT_SHAPES)
#undef PRISM_COUNT_SHAPES
  if (!sameCounts) {
    fault("built from another scene (" + counts + std::to_string(stats.planes) + " planes)");
  }
  const size_t materials = std::max<size_t>(1, scene.materials.size());  // Scene adds a default
  const auto check = [&](MaterialId id, const char* kind) {
    if (id >= materials) fault(std::string("a ") + kind + "'s material is past the scene's");
  };
#define PRISM_CHECK_SHAPE_MATERIALS(Shape, plural) \
  for (const Shape& shape : g.plural##_) check(shape.materialId(), Shape##Desc::kName.data());
  PRISM_SHAPE_KINDS(PRISM_CHECK_SHAPE_MATERIALS)
#undef PRISM_CHECK_SHAPE_MATERIALS
  for (const Plane& p : g.planes_) check(p.material, "plane");
  for (const SceneGeometry::MeshShading& m : g.meshes_) {
    check(m.material, "mesh");
    for (const MaterialId id : m.faceMaterials) check(id, "mesh face");
  }
}

size_t Fields<SceneGeometry>::wireBytes(const SceneGeometry& g) {
  size_t bytes = 4096 + g.triangles_.size() * sizeof(Triangle) + g.planes_.size() * 21 +
                 g.leafRefs_.size() * 4 + g.bvh_.nodes_.size() * sizeof(BvhNode) +
                 g.bvh_.order_.size() * 4 + g.wideBvh_.nodes_.size() * sizeof(WideBvhNode) +
                 g.packs_.size() * sizeof(SceneGeometry::LeafPack);
  for (const SceneGeometry::MeshShading& m : g.meshes_) {
    bytes += 64 + m.normals.size() * sizeof(Vec3) + m.indices.size() * 4 +
             m.uvs.size() * sizeof(Vec2) + m.colors.size() * sizeof(Color) +
             m.faceMaterials.size() * sizeof(MaterialId);
  }
  // Each shape with its caustic byte; a shape whose fields are sent one by one may take more
  // than its memory (a cone: 80 bytes in memory, 128 allowed).
#define PRISM_SHAPE_WIRE_BYTES(Shape, plural) bytes += g.plural##_.size() * (2 * sizeof(Shape) + 1);
  PRISM_SHAPE_KINDS(PRISM_SHAPE_WIRE_BYTES)
#undef PRISM_SHAPE_WIRE_BYTES
  return bytes;
}

void checkGeometryFitsScene(const SceneGeometry& geometry, const SceneDescription& scene) {
  Fields<SceneGeometry>::checkFitsScene(geometry, scene);
}

}  // namespace prism::wire
