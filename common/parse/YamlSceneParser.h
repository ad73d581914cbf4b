// Prism's YAML scene format (docs/scene-format.md is its reference).
#pragma once

#include <string>

#include "scene/SceneDescription.h"

namespace prism {

// Parses YAML scene text. path names the file in error messages and is the base for relative
// mesh and image paths. Throws SceneError with file:line:col on any problem.
SceneDescription parseYamlScene(const std::string& text, const std::string& path);

}  // namespace prism
