// The model files a scene may name (or that may be a scene: parse/SceneLoader.h), read by the
// loader their extension calls for, and placed into a scene.
#pragma once

#include <optional>
#include <string>

#include "scene/ModelDesc.h"
#include "util/MemorySize.h"

namespace prism {

// ".ply" through loadPlyMesh, ".gltf"/".glb" through loadGltfModel, anything else through
// loadObjModel (any case); the arguments and errors are theirs. referencedFrom is where a scene
// names the file (errors about a missing file point there).
ModelDesc loadModelFile(const std::string& path, const FileLoc& referencedFrom,
                        const MemoryLimit& limit = {});

// How a scene places a model.
struct ModelPlacement {
  // The scene's material for every face of every mesh (a YAML mesh's `material:`), overriding
  // the model's own; nothing: the model's materials (or the scene's default where it has none).
  std::optional<MaterialId> material;
  CausticRole caustic = CausticRole::Auto;
  FileLoc loc;              // where the scene places it
  bool takeCamera = false;  // the model's camera becomes the scene's, where it has one
  bool takeLights = false;  // the model's lights are added to the scene's
};

// Appends the model's meshes, materials and textures to scene (renumbering material and texture
// indices; a texture file the scene already holds is not added twice) and its warnings.
// With a placement's material the model's materials are not added. Returns the index of the
// first mesh added.
size_t placeModel(ModelDesc model, const ModelPlacement& placement, SceneDescription& scene);

}  // namespace prism
