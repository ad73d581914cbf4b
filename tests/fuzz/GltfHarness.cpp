#include "fuzz/Harnesses.h"
#include "fuzz/SceneInvariants.h"
#include "parse/GltfLoader.h"

namespace prism::fuzz {

namespace {

// Enough for any seed; far less than a fuzzer's RSS limit, so an accessor that claims a billion
// vertices is refused from its count, as a render would refuse it.
const MemoryLimit kLimit{256ull << 20, "the fuzz harness"};

// A glTF's outcome: SceneError is a clean rejection; an accepted model's meshes must pass
// checkMesh and hold triangles, and its material and texture indices must point into its lists.
Outcome modelOutcome(std::string_view bytes, const std::string& name) {
  ModelDesc model;
  try {
    // External files are never there: only data URIs and a .glb's binary chunk are read.
    model = parseGltfModel(
        bytes, name, [](const std::string&) { return std::optional<std::string_view>(); },
        FileLoc{"fuzz-input.yaml", 1, 1}, kLimit);
  } catch (const SceneError&) {
    return Outcome::Rejected;
  }
  if (model.meshes.empty()) throw InvariantBroken("accepted a model without meshes");
  for (const MeshDesc& mesh : model.meshes) {
    checkMesh(mesh);
    if (mesh.indices.empty()) throw InvariantBroken("accepted a mesh without triangles");
    if (mesh.material >= model.materials.size()) throw InvariantBroken("material out of range");
    if (!mesh.uvs.empty() && mesh.uvs.size() != mesh.positions.size()) {
      throw InvariantBroken("uvs do not match the positions");
    }
    if (!mesh.colors.empty() && mesh.colors.size() != mesh.positions.size()) {
      throw InvariantBroken("colours do not match the positions");
    }
  }
  for (const MaterialDesc& material : model.materials) {
    if (material.diffuseMap && material.diffuseMap->texture >= model.textures.size()) {
      throw InvariantBroken("texture out of range");
    }
  }
  return Outcome::Accepted;
}

}  // namespace

Outcome fuzzGltf(const uint8_t* data, size_t size) {
  return modelOutcome({reinterpret_cast<const char*>(data), size}, "fuzz-input.gltf");
}

Outcome fuzzGlb(const uint8_t* data, size_t size) {
  return modelOutcome({reinterpret_cast<const char*>(data), size}, "fuzz-input.glb");
}

}  // namespace prism::fuzz
