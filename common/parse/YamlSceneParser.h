// Prism's YAML scene format (docs/scene-format.md is its reference).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "scene/SceneDescription.h"
#include "util/MemorySize.h"

namespace prism {

// Parses YAML scene text. path names the file in error messages and is the base for relative
// mesh and image paths. Throws SceneError with file:line:col on any problem.
// Meshes the scene names are refused before they are read when, with the meshes before them,
// they would pass limit (parse/ObjLoader.h).
SceneDescription parseYamlScene(const std::string& text, const std::string& path,
                                const MemoryLimit& limit = {});

// Every key the parser accepts, by section ("top level", "camera", "materials", "sphere",
// "transform", ...): each section is a heading in docs/scene-format.md, and a test checks that
// every key is documented under it.
const std::map<std::string, std::vector<std::string>>& yamlSceneKeys();

}  // namespace prism
