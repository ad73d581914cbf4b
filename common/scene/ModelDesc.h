// What a model file brings (an OBJ with its MTL files and textures, a PLY, a glTF): meshes whose
// materials index the model's own material list, materials whose texture maps index its own
// texture list, and the file's camera and lights where it has them. A scene places a model with
// placeModel (parse/ModelFile.h), which renumbers both lists into the scene's.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scene/SceneDescription.h"

namespace prism {

struct ModelDesc {
  std::string source;  // the file
  std::vector<MeshDesc> meshes;
  std::vector<MaterialDesc> materials;  // empty: the meshes' material 0 is the scene's choice
  std::vector<TextureDesc> textures;
  std::optional<CameraDesc> camera;  // the file's own (glTF: the first camera of the scene)
  std::vector<PointLightDesc> lights;
  // What the file holds that Prism does not model or could not use, each kind once:
  // "file:line: what was skipped, and what is used instead".
  std::vector<std::string> warnings;

  size_t triangleCount() const {
    size_t n = 0;
    for (const MeshDesc& m : meshes) n += m.triangleCount();
    return n;
  }
};

}  // namespace prism
