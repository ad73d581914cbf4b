#include "parse/GltfMesh.h"

#include <atomic>
#include <cmath>
#include <limits>

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "scene/MeshBudget.h"
#include "util/HugePages.h"
#include "util/Parallel.h"

namespace prism {

namespace {

constexpr int kTriangles = 4, kStrip = 5, kFan = 6;
constexpr uint64_t kBlock = 1 << 16;  // items a thread handles at a time

// The smallest i in [0, count) for which bad(i) holds, or count; checked on every core.
template <class Bad>
uint64_t firstWhere(uint64_t count, Bad bad) {
  std::atomic<uint64_t> first{count};
  forChunks(count, kBlock, 0, [&](uint64_t begin, uint64_t end) {
    for (uint64_t i = begin; i < end && i < first.load(std::memory_order_relaxed); ++i) {
      if (!bad(i)) continue;
      uint64_t seen = first.load();
      while (i < seen && !first.compare_exchange_weak(seen, i)) {
      }
      return;
    }
  });
  return first.load();
}
constexpr uint32_t kU8 = 5121, kU16 = 5123, kU32 = 5125;

GltfAccessor attribute(const GltfDocument& doc, const GltfJson& ref, const char* name,
                       std::initializer_list<int> components, uint64_t count) {
  GltfAccessor a = viewAccessor(doc, ref.index(), ref);
  bool typeOk = false;
  for (int c : components) typeOk = typeOk || a.components == c;
  if (!typeOk)
    ref.fail(std::string(name) + " has " + std::to_string(a.components) +
             " components per element");
  if (count != 0 && a.count != count) {
    ref.fail(std::string(name) + " has " + std::to_string(a.count) + " elements, POSITION has " +
             std::to_string(count));
  }
  return a;
}

GltfPrimitivePlan planPrimitive(GltfDocument& doc, const GltfJson& primitive, uint64_t mesh,
                                uint64_t index) {
  GltfPrimitivePlan plan;
  plan.mesh = mesh;
  plan.primitive = index;
  plan.path = primitive.path();
  const GltfJson attributes = primitive.required("attributes");
  plan.position = attribute(doc, attributes.required("POSITION"), "POSITION", {3}, 0);
  plan.vertices = plan.position.count;
  if (plan.vertices > std::numeric_limits<uint32_t>::max()) {
    attributes.required("POSITION").fail("more than 2^32 vertices in one primitive");
  }
  for (const std::string_view name : attributes.keys()) {
    const GltfJson ref = attributes.required(name);
    if (name == "NORMAL") {
      plan.normal = attribute(doc, ref, "NORMAL", {3}, plan.vertices);
    } else if (name == "TEXCOORD_0") {
      plan.texcoord = attribute(doc, ref, "TEXCOORD_0", {2}, plan.vertices);
    } else if (name == "COLOR_0") {
      plan.color = attribute(doc, ref, "COLOR_0", {3, 4}, plan.vertices);
    } else if (name != "POSITION") {
      doc.warn("attribute " + std::string(name),
               ref.path() +
                   ": the attribute is not read (Prism reads POSITION, NORMAL, "
                   "TEXCOORD_0 and COLOR_0)");
    }
  }
  if (primitive.member("targets")) {
    doc.warn("morph targets", primitive.path() +
                                  ".targets: morph targets are not modelled: "
                                  "the base shape is rendered");
  }
  plan.material = primitive.optionalIndex("material");
  if (plan.material)
    doc.at(doc.materials, *plan.material, *primitive.member("material"), "materials");
  if (const std::optional<GltfJson> indices = primitive.member("indices")) {
    plan.indices = viewAccessor(doc, indices->index(), *indices);
    const uint32_t type = plan.indices->componentType;
    if (plan.indices->components != 1 || (type != kU8 && type != kU16 && type != kU32)) {
      indices->fail("indices must be SCALAR unsigned bytes, shorts or ints");
    }
  }
  return plan;
}

// The index list as triangles: lists as they are, strips and fans converted (glTF 2.0 §3.7.2.1:
// strip triangle i is (i, i+1+i%2, i+2−i%2), fan triangle i is (i+1, i+2, 0)).
void triangulate(int mode, const std::vector<uint32_t>& in, uint64_t triangles,
                 std::vector<uint32_t>& out) {
  out.resize(3 * triangles);
  for (uint64_t t = 0; t < triangles; ++t) {
    uint32_t* o = &out[3 * t];
    if (mode == kStrip) {
      o[0] = in[t];
      o[1] = in[t + 1 + t % 2];
      o[2] = in[t + 2 - t % 2];
    } else {
      o[0] = in[t + 1];
      o[1] = in[t + 2];
      o[2] = in[0];
    }
  }
}

void readTriangleIndices(const GltfPrimitivePlan& plan, MeshDesc& mesh) {
  const uint64_t n = plan.indices ? plan.indices->count : plan.vertices;
  std::vector<uint32_t> raw;
  std::vector<uint32_t>& target = plan.mode == kTriangles ? mesh.indices : raw;
  reserveOnHugePages(target, n);
  target.resize(n);
  uint64_t largest = n - 1;
  if (plan.indices) {
    largest = readIndices(*plan.indices, target.data());
  } else {
    for (uint64_t i = 0; i < n; ++i) target[i] = static_cast<uint32_t>(i);
  }
  if (plan.mode == kTriangles) {
    mesh.indices.resize(3 * plan.triangles);  // a list's trailing partial triangle is dropped
  } else {
    triangulate(plan.mode, raw, plan.triangles, mesh.indices);
  }
  if (largest < plan.vertices) return;
  // Some index may be out of range (or was replaced by a sparse value): find the first.
  const uint32_t* indices = mesh.indices.data();
  const uint64_t bad =
      firstWhere(mesh.indices.size(), [&](uint64_t i) { return indices[i] >= plan.vertices; });
  if (bad < mesh.indices.size()) {
    const std::string& at = plan.indices ? plan.indices->path : plan.path;
    throw SceneError(FileLoc{plan.position.file, 0, 0},
                     at + ": index " + std::to_string(indices[bad]) + " is out of range (" +
                         plan.path + " has " + std::to_string(plan.vertices) + " vertices)");
  }
}

void readPositions(const GltfPrimitivePlan& plan, const glm::mat4& world, MeshDesc& mesh) {
  reserveOnHugePages(mesh.positions, plan.vertices);
  mesh.positions.resize(plan.vertices);
  readFloats(plan.position, 3, &mesh.positions[0].x);
  const bool identity = world == glm::mat4(1.0f);
  Vec3* positions = mesh.positions.data();
  const uint64_t bad = firstWhere(plan.vertices, [&](uint64_t i) {
    if (!identity) positions[i] = Vec3(world * glm::vec4(positions[i], 1.0f));
    return !isFinite(positions[i]);
  });
  if (bad < plan.vertices) {
    throw SceneError(FileLoc{plan.position.file, 0, 0},
                     plan.position.path + ": position " + std::to_string(bad) +
                         " is not finite (as read, or once the node's transform is applied)");
  }
}

void readNormals(const GltfPrimitivePlan& plan, const glm::mat4& world, MeshDesc& mesh) {
  reserveOnHugePages(mesh.normals, plan.vertices);
  mesh.normals.resize(plan.vertices);
  readFloats(*plan.normal, 3, &mesh.normals[0].x);
  const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(world)));
  const bool identity = normalMatrix == glm::mat3(1.0f);
  Vec3* normals = mesh.normals.data();
  const uint64_t bad = firstWhere(plan.vertices, [&](uint64_t i) {
    const Vec3 n = identity ? normals[i] : normalMatrix * normals[i];
    // As isUsableNormal, with one square root: a squared length below the smallest normal float
    // (or not finite) does not normalise to a unit vector.
    const float length2 = glm::dot(n, n);
    if (!(length2 >= std::numeric_limits<float>::min()) || !std::isfinite(length2)) return true;
    normals[i] = n * (1.0f / std::sqrt(length2));
    return false;
  });
  if (bad < plan.vertices) std::vector<Vec3>().swap(mesh.normals);  // flat, as a PLY or OBJ mesh
}

}  // namespace

std::vector<std::vector<GltfPrimitivePlan>> planGltfMeshes(GltfDocument& doc,
                                                           const std::vector<bool>& used) {
  std::vector<std::vector<GltfPrimitivePlan>> plans(doc.meshes.size());
  for (size_t m = 0; m < doc.meshes.size(); ++m) {
    if (!used[m]) continue;
    const std::vector<GltfJson> primitives = doc.meshes[m].required("primitives").items();
    for (size_t p = 0; p < primitives.size(); ++p) {
      primitives[p].expectObject();
      const uint64_t mode = primitives[p].indexOr("mode", kTriangles);
      if (mode > kFan)
        primitives[p].required("mode").fail("unknown primitive mode " + std::to_string(mode));
      if (mode < kTriangles) {
        doc.warn("points and lines",
                 primitives[p].path() + ": points and lines are not rendered: skipped");
        continue;
      }
      GltfPrimitivePlan plan = planPrimitive(doc, primitives[p], m, p);
      plan.mode = static_cast<int>(mode);
      const uint64_t n = plan.indices ? plan.indices->count : plan.vertices;
      plan.triangles = plan.mode == kTriangles ? n / 3 : n >= 3 ? n - 2 : 0;
      plans[m].push_back(std::move(plan));
    }
  }
  return plans;
}

uint64_t gltfPrimitiveBytes(const GltfPrimitivePlan& plan) {
  const uint64_t perVertex =
      12 + (plan.normal ? 12 : 0) + (plan.texcoord ? 8 : 0) + (plan.color ? 12 : 0);
  const uint64_t n = plan.indices ? plan.indices->count : plan.vertices;
  uint64_t bytes = saturatingMultiply(plan.vertices, perVertex);
  bytes = saturatingAdd(bytes, saturatingMultiply(n, plan.mode == kTriangles ? 4 : 8));
  bytes = saturatingAdd(bytes, saturatingMultiply(plan.triangles, 12));
  return saturatingAdd(bytes, meshBuildBytes(plan.triangles, plan.vertices));
}

MeshDesc readGltfPrimitive(const GltfDocument& doc, const GltfPrimitivePlan& plan,
                           const GltfMeshInstance& instance, uint32_t noMaterial) {
  MeshDesc mesh;
  mesh.source = doc.file + " " + plan.path + " at " + instance.node;
  mesh.loc = FileLoc{doc.file, 0, 0};
  mesh.material = plan.material ? static_cast<MaterialId>(*plan.material) : noMaterial;
  readTriangleIndices(plan, mesh);
  readPositions(plan, instance.world, mesh);
  if (plan.normal) readNormals(plan, instance.world, mesh);
  if (plan.texcoord) {
    mesh.uvs.resize(plan.vertices);
    readFloats(*plan.texcoord, 2, &mesh.uvs[0].x);
    for (Vec2& uv : mesh.uvs) uv.y = 1.0f - uv.y;  // glTF's v runs down the image, Prism's up
  }
  if (plan.color) {
    mesh.colors.resize(plan.vertices);
    readFloats(*plan.color, 3, &mesh.colors[0].x);
  }
  if (glm::determinant(glm::mat3(instance.world)) < 0.0f) {
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
      std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
  }
  return mesh;
}

}  // namespace prism
