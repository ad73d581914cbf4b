// The default scene of a glTF (`scene`, else scenes[0], else every root node) walked in order:
// each node's world transform (its parents' composed with its own matrix or translation ·
// rotation · scale), the meshes it places, the first camera and the punctual lights. A node
// graph that is not a forest (a cycle, a node with two parents) is refused.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

#include "parse/GltfDocument.h"
#include "scene/SceneDescription.h"

namespace prism {

struct GltfMeshInstance {
  uint64_t mesh = 0;
  glm::mat4 world{1.0f};
  std::string node;  // "nodes[4]", for messages
};

struct GltfSceneContents {
  std::vector<GltfMeshInstance> meshes;
  std::optional<CameraDesc> camera;  // the first in traversal order
  std::vector<PointLightDesc> lights;
};

GltfSceneContents walkGltfScene(GltfDocument& doc);

// KHR_lights_punctual's candela (lm/sr) as Prism's W/sr: 1 W of 555 nm light is 683 lm.
inline constexpr float kLumensPerWatt = 683.0f;

}  // namespace prism
