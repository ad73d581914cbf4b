#include "parse/ModelFile.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <unordered_map>

#include "parse/GltfLoader.h"
#include "parse/ObjLoader.h"
#include "parse/PlyLoader.h"

namespace prism {

ModelDesc loadModelFile(const std::string& path, const FileLoc& referencedFrom,
                        const MemoryLimit& limit) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".gltf" || extension == ".glb") {
    return loadGltfModel(path, referencedFrom, limit);
  }
  if (extension != ".ply") return loadObjModel(path, referencedFrom, limit);
  ModelDesc model;
  model.source = path;
  model.meshes.push_back(loadPlyMesh(path, referencedFrom, limit));
  return model;
}

size_t placeModel(ModelDesc model, const ModelPlacement& placement, SceneDescription& scene) {
  // Textures by file: one the scene already holds (another model's material named it) is read
  // from there.
  std::vector<uint32_t> textureIndex(model.textures.size());
  std::unordered_map<std::string, uint32_t> held;
  for (size_t i = 0; i < scene.textures.size(); ++i) {
    held.emplace(scene.textures[i].path, static_cast<uint32_t>(i));
  }
  const bool ownMaterials = !placement.material && !model.materials.empty();
  if (ownMaterials) {
    for (size_t i = 0; i < model.textures.size(); ++i) {
      const auto [it, added] =
          held.emplace(model.textures[i].path, static_cast<uint32_t>(scene.textures.size()));
      if (added) scene.textures.push_back(std::move(model.textures[i]));
      textureIndex[i] = it->second;
    }
  }
  const auto firstMaterial = static_cast<MaterialId>(scene.materials.size());
  if (ownMaterials) {
    for (MaterialDesc& material : model.materials) {
      if (material.diffuseMap)
        material.diffuseMap->texture = textureIndex[material.diffuseMap->texture];
      scene.materials.push_back(std::move(material));
    }
  }
  const size_t firstMesh = scene.meshes.size();
  for (MeshDesc& mesh : model.meshes) {
    if (placement.material) {
      mesh.material = *placement.material;
      mesh.faceMaterials.clear();
    } else if (ownMaterials) {
      mesh.material += firstMaterial;
      for (MaterialId& id : mesh.faceMaterials) id += firstMaterial;
    } else {
      mesh.material = 0;
      mesh.faceMaterials.clear();
    }
    mesh.caustic = placement.caustic;
    if (!placement.loc.file.empty()) mesh.loc = placement.loc;
    scene.meshes.push_back(std::move(mesh));
  }
  if (placement.takeCamera && model.camera) scene.camera = *model.camera;
  if (placement.takeLights) {
    for (PointLightDesc& light : model.lights) scene.lights.push_back(std::move(light));
  }
  for (std::string& warning : model.warnings) scene.warnings.push_back(std::move(warning));
  return firstMesh;
}

}  // namespace prism
