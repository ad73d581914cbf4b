#include "fuzz/SceneInvariants.h"

#include <algorithm>
#include <cmath>

#include "fuzz/Harnesses.h"
#include "parse/ModelFile.h"
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

namespace {

bool isUsableColor(const Color& c) {
  return isFinite(c) && c.r >= 0.0f && c.g >= 0.0f && c.b >= 0.0f;
}

}  // namespace

void checkModel(const ModelDesc& model) {
  for (const MeshDesc& mesh : model.meshes) {
    checkMesh(mesh);
    for (const Vec2& uv : mesh.uvs) {
      if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) {
        throw InvariantBroken("non-finite texture coordinate");
      }
    }
    for (const Color& c : mesh.colors) {
      if (!isUsableColor(c)) throw InvariantBroken("non-finite or negative vertex colour");
    }
    const size_t materials = std::max<size_t>(model.materials.size(), 1);
    if (mesh.material >= materials) throw InvariantBroken("mesh material past the model's");
    for (const MaterialId id : mesh.faceMaterials) {
      if (id >= materials) throw InvariantBroken("face material past the model's");
    }
  }
  for (const MaterialDesc& m : model.materials) {
    for (const Color& c : {m.ambient, m.diffuse, m.specular, m.reflectance, m.transmittance}) {
      if (!isUsableColor(c)) throw InvariantBroken("non-finite or negative material colour");
    }
    if (!std::isfinite(m.shininess) || m.shininess < 0.0f) {
      throw InvariantBroken("non-finite or negative shininess");
    }
    if (!std::isfinite(m.ior) || m.ior < 1.0f) throw InvariantBroken("ior below 1");
    if (m.diffuseMap) {
      if (m.diffuseMap->texture >= model.textures.size()) {
        throw InvariantBroken("texture map past the model's textures");
      }
      const TextureMap& map = *m.diffuseMap;
      if (!std::isfinite(map.scale.x) || !std::isfinite(map.scale.y) ||
          !std::isfinite(map.offset.x) || !std::isfinite(map.offset.y) ||
          !std::isfinite(map.rotation)) {
        throw InvariantBroken("non-finite texture placement");
      }
    }
  }
  SceneDescription scene;
  placeModel(model, ModelPlacement{}, scene);
  checkScene(scene);
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
