#include "fuzz/SceneInvariants.h"

#include "fuzz/Harnesses.h"
#include "wire/Messages.h"

namespace prism::fuzz {

void checkScene(const SceneDescription& scene) {
  try {
    wire::decodeScene(wire::decodeMessage(wire::encodeScene(scene)));
  } catch (const wire::WireError& error) {
    throw InvariantBroken(std::string("parsed scene is refused by the wire decoder: ") +
                          error.what());
  }
  for (const MeshDesc& mesh : scene.meshes) checkMesh(mesh);
}

void checkMesh(const MeshDesc& mesh) {
  if (mesh.indices.size() % 3 != 0) throw InvariantBroken("index count not a multiple of 3");
  if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size()) {
    throw InvariantBroken("normal count differs from position count");
  }
  for (uint32_t index : mesh.indices) {
    if (index >= mesh.positions.size()) throw InvariantBroken("index past the positions");
  }
  for (const Vec3& p : mesh.positions) {
    if (!isFinite(p)) throw InvariantBroken("non-finite position");
  }
  for (const Vec3& n : mesh.normals) {
    if (!isFinite(n)) throw InvariantBroken("non-finite normal");
  }
}

}  // namespace prism::fuzz
